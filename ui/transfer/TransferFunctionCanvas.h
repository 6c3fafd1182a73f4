#pragma once

#include <functional>
#include <optional>

#include <QColor>
#include <QPointF>
#include <QRectF>
#include <QWidget>

#include "core/tf/TransferFunction.h"
#include "core/tf/VolumeHistogram.h"

namespace lucent {

// The drawing and mouse part of the transfer-function editor: the volume's
// histogram (log scale) behind the opacity curve, opacity points above and a
// colour strip with its stops below. The value axis runs left to right over the
// histogram's range and the function's points; opacity runs bottom (0) to top (1).
//
// Opacity points: left-drag moves one (between its neighbours), double-click on
// empty space adds one, right-click or Delete (on the selected one) removes one.
// Colour stops: left-drag moves one, double-click on the strip edits a stop's
// colour or adds a stop, right-click removes one. At least one point and one stop
// always remain. Every edit emits transferFunctionChanged, while dragging too.
class TransferFunctionCanvas : public QWidget {
    Q_OBJECT

public:
    // Asked for a colour when a stop is added or edited; nullopt cancels.
    // The default opens QColorDialog.
    using ColourPicker = std::function<std::optional<QColor>(const QColor& initial)>;

    explicit TransferFunctionCanvas(QWidget* parent = nullptr);

    // Replaces the function without emitting (the caller knows).
    void setTransferFunction(const TransferFunction& tf);
    const TransferFunction& transferFunction() const { return tf_; }
    void setHistogram(VolumeHistogram histogram);
    const VolumeHistogram& histogram() const { return histogram_; }
    void setColourPicker(ColourPicker picker) { colourPicker_ = std::move(picker); }

    // The value range shown: the histogram's and the function's points together.
    double valueLo() const { return valueLo_; }
    double valueHi() const { return valueHi_; }
    QRectF opacityArea() const;
    QRectF colourStrip() const;
    double xOfValue(double value) const;
    double valueAtX(double x) const;
    double yOfOpacity(double opacity) const;
    double opacityAtY(double y) const;
    QPointF opacityPointPosition(int index) const;
    QPointF colourStopPosition(int index) const;
    int selectedOpacityPoint() const { return selected_; }

    QSize sizeHint() const override { return {420, 200}; }
    QSize minimumSizeHint() const override { return {200, 100}; }

signals:
    void transferFunctionChanged(const lucent::TransferFunction& tf);

protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void mouseDoubleClickEvent(QMouseEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;

private:
    int opacityPointAt(const QPointF& pos) const;
    int colourStopAt(const QPointF& pos) const;
    void updateValueRange();
    // The value clamped strictly between the neighbours of entry `index`.
    template <class Points>
    double clampBetweenNeighbours(const Points& points, int index, double value) const;
    void addOpacityPoint(const QPointF& pos);
    void removeOpacityPoint(int index);
    void editColourStop(int index);
    void addColourStop(double value);
    void changed();
    void paintHistogram(QPainter& painter, const QRectF& area) const;
    void paintColourStrip(QPainter& painter, const QRectF& strip) const;

    TransferFunction tf_;
    VolumeHistogram histogram_;
    double valueLo_ = 0.0;
    double valueHi_ = 1.0;
    ColourPicker colourPicker_;

    enum class Drag { None, OpacityPoint, ColourStop };
    Drag drag_ = Drag::None;
    int dragIndex_ = -1;
    int selected_ = -1;
};

} // namespace lucent
