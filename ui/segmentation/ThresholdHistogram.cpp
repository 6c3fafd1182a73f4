#include "ui/segmentation/ThresholdHistogram.h"

#include <QMouseEvent>
#include <QPainter>

#include <algorithm>
#include <cmath>

namespace lucent {

ThresholdHistogram::ThresholdHistogram(QWidget* parent) : QWidget(parent) {
    setMinimumHeight(40);
    setToolTip(tr("The series' values (log counts) and the threshold's range; press or drag "
                  "to move the nearer end"));
}

void ThresholdHistogram::setHistogram(VolumeHistogram histogram) {
    histogram_ = std::move(histogram);
    update();
}

void ThresholdHistogram::setRange(double lo, double hi) {
    lo_ = std::min(lo, hi);
    hi_ = std::max(lo, hi);
    update();
}

double ThresholdHistogram::valueAt(double x) const {
    const double f = std::clamp(x / std::max(1, width() - 1), 0.0, 1.0);
    return histogram_.lo + f * (histogram_.hi - histogram_.lo);
}

double ThresholdHistogram::xOf(double value) const {
    return (value - histogram_.lo) / (histogram_.hi - histogram_.lo) * (width() - 1);
}

void ThresholdHistogram::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    painter.fillRect(rect(), QColor(30, 30, 34));
    if (histogram_.counts.empty()) {
        return;
    }
    const double x0 = std::clamp(xOf(lo_), 0.0, double(width()));
    const double x1 = std::clamp(xOf(hi_), 0.0, double(width()));
    painter.fillRect(QRectF(x0, 0, std::max(1.0, x1 - x0), height()), QColor(70, 110, 70));
    const double top = std::log1p(double(histogram_.largestCount()));
    const double binWidth = double(width()) / double(histogram_.counts.size());
    painter.setPen(Qt::NoPen);
    painter.setBrush(QColor(150, 150, 160));
    for (std::size_t n = 0; n < histogram_.counts.size(); ++n) {
        const double h = top > 0.0 ? std::log1p(double(histogram_.counts[n])) / top : 0.0;
        painter.drawRect(QRectF(n * binWidth, height() * (1.0 - h), binWidth, height() * h));
    }
    painter.setPen(QPen(QColor(120, 230, 120), 2.0));
    painter.drawLine(QPointF(x0, 0), QPointF(x0, height()));
    painter.drawLine(QPointF(x1, 0), QPointF(x1, height()));
}

void ThresholdHistogram::mousePressEvent(QMouseEvent* event) {
    if (event->button() != Qt::LeftButton || histogram_.counts.empty()) {
        return;
    }
    const double value = valueAt(event->position().x());
    draggingUpper_ = std::abs(value - hi_) < std::abs(value - lo_);
    mouseMoveEvent(event);
}

void ThresholdHistogram::mouseMoveEvent(QMouseEvent* event) {
    if (!(event->buttons() & Qt::LeftButton) || histogram_.counts.empty()) {
        return;
    }
    const double value = std::round(valueAt(event->position().x()));
    if (draggingUpper_) {
        setRange(lo_, std::max(value, lo_));
    } else {
        setRange(std::min(value, hi_), hi_);
    }
    emit rangeChosen(lo_, hi_);
}

} // namespace lucent
