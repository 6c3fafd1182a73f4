#include "PlotCanvas.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lucent::cli {
namespace {

constexpr int kW = 900, kH = 600, kLeft = 70, kRight = 20, kTop = 40, kBottom = 60;
constexpr double kSmallest = 1e-3; // a zero along x is drawn here

double logOf(double v, double base) {
    return std::log(std::max(v, kSmallest)) / std::log(base);
}

} // namespace

PlotCanvas::PlotCanvas(const PlotAxes& axes)
    : image_(kW, kH, QImage::Format_RGB32), base_(axes.base), yMin_(axes.yMin), yMax_(axes.yMax) {
    decadeLo_ = std::floor(logOf(axes.xLo, base_));
    decadeHi_ = std::max(std::ceil(logOf(axes.xHi, base_)), decadeLo_ + 1);
    image_.fill(Qt::white);
    painter_.begin(&image_);
    painter_.setRenderHint(QPainter::Antialiasing);
    drawAxes(axes);
}

double PlotCanvas::x(double value) const {
    return kLeft +
           (logOf(value, base_) - decadeLo_) / (decadeHi_ - decadeLo_) * (kW - kLeft - kRight);
}

double PlotCanvas::y(double value) const {
    const double v = std::clamp(std::isfinite(value) ? value : yMax_, yMin_, yMax_);
    return kTop + (yMax_ - v) / (yMax_ - yMin_) * (kH - kTop - kBottom);
}

void PlotCanvas::drawAxes(const PlotAxes& axes) {
    QPainter& p = painter_;
    if (axes.band) {
        p.fillRect(
            QRectF(QPointF(kLeft, y(axes.band->yHi)), QPointF(kW - kRight, y(axes.band->yLo))),
            axes.band->colour);
    }
    p.setPen(QColor(120, 120, 120));
    for (double d = yMin_; d <= yMax_; d += axes.yStep) {
        p.drawLine(QPointF(kLeft - 4, y(d)), QPointF(kLeft, y(d)));
        p.drawText(QRectF(0, y(d) - 8, kLeft - 8, 16), Qt::AlignRight | Qt::AlignVCenter,
                   QString::number(d));
    }
    for (double e = decadeLo_; e <= decadeHi_; e += 1) {
        const double value = std::pow(base_, e);
        p.drawLine(QPointF(x(value), kH - kBottom), QPointF(x(value), kH - kBottom + 4));
        p.drawText(QRectF(x(value) - 40, kH - kBottom + 6, 80, 16), Qt::AlignCenter,
                   QString::number(value) + axes.xUnit);
    }
    p.drawRect(QRectF(QPointF(kLeft, kTop), QPointF(kW - kRight, kH - kBottom)));
    p.setPen(Qt::black);
    p.drawText(QRectF(0, 8, kW, 20), Qt::AlignCenter, axes.title);
    p.drawText(QRectF(0, kH - 28, kW, 20), Qt::AlignCenter, axes.caption);
    p.save();
    p.translate(16, kH / 2.0);
    p.rotate(-90);
    p.drawText(QRectF(-120, -10, 240, 20), Qt::AlignCenter, axes.yLabel);
    p.restore();
}

void PlotCanvas::save(const QString& path) {
    painter_.end();
    if (!image_.save(path, "PNG")) {
        throw std::runtime_error("cannot write the plot " + path.toStdString());
    }
}

} // namespace lucent::cli
