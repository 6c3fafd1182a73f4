#pragma once

#include <QColor>
#include <QImage>
#include <QPainter>
#include <QString>

#include <optional>

namespace lucent::cli {

// What the benches' charts share: a logarithmic x axis (whole powers of `base`
// around the data), a linear y axis of PSNR, a title, a caption under the
// axis, a label along y, and optionally a shaded band of y values.
struct PlotAxes {
    double base = 10.0;           // of the x axis's logarithm
    double xLo = 1.0, xHi = 10.0; // the data's extent along x (above 0)
    QString xUnit;                // after each tick's value, e.g. " ms"
    double yMin = 0.0, yMax = 1.0, yStep = 1.0;
    QString title, caption, yLabel;
    struct Band {
        double yLo, yHi;
        QColor colour;
    };
    std::optional<Band> band;
};

// A 900x600 PNG chart with the axes drawn; the caller draws its points at
// x() and y() with painter(), then save()s. Needs a QGuiApplication (fonts).
class PlotCanvas {
public:
    explicit PlotCanvas(const PlotAxes& axes);
    PlotCanvas(const PlotCanvas&) = delete;
    PlotCanvas& operator=(const PlotCanvas&) = delete;

    QPainter& painter() { return painter_; }
    double x(double value) const;
    // Infinite PSNR (identical images) is drawn at the top of the scale.
    double y(double value) const;
    // Throws std::runtime_error when the file cannot be written.
    void save(const QString& path);

private:
    void drawAxes(const PlotAxes& axes);

    QImage image_;
    QPainter painter_;
    double base_, decadeLo_, decadeHi_, yMin_, yMax_;
};

} // namespace lucent::cli
