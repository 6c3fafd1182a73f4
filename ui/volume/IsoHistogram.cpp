#include "ui/volume/IsoHistogram.h"

#include <QMouseEvent>
#include <QPainter>

#include <algorithm>
#include <cmath>

namespace lucent {

IsoHistogram::IsoHistogram(QWidget* parent) : QWidget(parent) {
    setMinimumHeight(36);
    setToolTip(tr("The volume's values (log counts); click to set the iso value"));
}

void IsoHistogram::setHistogram(VolumeHistogram histogram) {
    histogram_ = std::move(histogram);
    update();
}

void IsoHistogram::setIsoValue(double value) {
    iso_ = value;
    update();
}

double IsoHistogram::valueAt(double x) const {
    const double f = std::clamp(x / std::max(1, width() - 1), 0.0, 1.0);
    return histogram_.lo + f * (histogram_.hi - histogram_.lo);
}

void IsoHistogram::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    painter.fillRect(rect(), QColor(30, 30, 34));
    if (histogram_.counts.empty()) {
        return;
    }
    const double top = std::log1p(double(histogram_.largestCount()));
    const double binWidth = double(width()) / double(histogram_.counts.size());
    painter.setPen(Qt::NoPen);
    painter.setBrush(QColor(130, 130, 140));
    for (std::size_t n = 0; n < histogram_.counts.size(); ++n) {
        const double h = top > 0.0 ? std::log1p(double(histogram_.counts[n])) / top : 0.0;
        painter.drawRect(QRectF(n * binWidth, height() * (1.0 - h), binWidth, height() * h));
    }
    const double x = (iso_ - histogram_.lo) / (histogram_.hi - histogram_.lo) * (width() - 1);
    painter.setPen(QPen(QColor(255, 200, 80), 2.0));
    painter.drawLine(QPointF(x, 0), QPointF(x, height()));
}

void IsoHistogram::mousePressEvent(QMouseEvent* event) {
    if (event->button() == Qt::LeftButton && !histogram_.counts.empty()) {
        emit isoValueChosen(valueAt(event->position().x()));
    }
}

void IsoHistogram::mouseMoveEvent(QMouseEvent* event) {
    if ((event->buttons() & Qt::LeftButton) && !histogram_.counts.empty()) {
        emit isoValueChosen(valueAt(event->position().x()));
    }
}

} // namespace lucent
