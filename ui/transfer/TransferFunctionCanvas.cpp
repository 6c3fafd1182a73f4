#include "ui/transfer/TransferFunctionCanvas.h"

#include <algorithm>
#include <cmath>

#include <QColorDialog>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>

namespace lucent {

namespace {

constexpr double kMargin = 8.0;
constexpr double kStripHeight = 18.0;
constexpr double kStripGap = 6.0;
constexpr double kHitRadius = 7.0;

QColor toQColor(const glm::dvec3& rgb) {
    return QColor::fromRgbF(static_cast<float>(std::clamp(rgb.r, 0.0, 1.0)),
                            static_cast<float>(std::clamp(rgb.g, 0.0, 1.0)),
                            static_cast<float>(std::clamp(rgb.b, 0.0, 1.0)));
}

glm::dvec3 toRgb(const QColor& c) {
    return {c.redF(), c.greenF(), c.blueF()};
}

} // namespace

TransferFunctionCanvas::TransferFunctionCanvas(QWidget* parent) : QWidget(parent) {
    setFocusPolicy(Qt::StrongFocus);
    setMouseTracking(false);
    colourPicker_ = [this](const QColor& initial) -> std::optional<QColor> {
        const QColor c = QColorDialog::getColor(initial, this, tr("Colour stop"));
        return c.isValid() ? std::optional<QColor>(c) : std::nullopt;
    };
    tf_.opacity = {{0.0, 0.0}, {1.0, 1.0}};
    tf_.colour = {{0.0, glm::dvec3(1.0)}};
    updateValueRange();
}

void TransferFunctionCanvas::setTransferFunction(const TransferFunction& tf) {
    tf_ = tf;
    drag_ = Drag::None;
    selected_ = std::min(selected_, static_cast<int>(tf_.opacity.size()) - 1);
    updateValueRange();
    update();
}

void TransferFunctionCanvas::setHistogram(VolumeHistogram histogram) {
    histogram_ = std::move(histogram);
    updateValueRange();
    update();
}

void TransferFunctionCanvas::updateValueRange() {
    double lo = histogram_.counts.empty() ? 1e300 : histogram_.lo;
    double hi = histogram_.counts.empty() ? -1e300 : histogram_.hi;
    for (const auto& p : tf_.opacity) {
        lo = std::min(lo, p.value);
        hi = std::max(hi, p.value);
    }
    for (const auto& c : tf_.colour) {
        lo = std::min(lo, c.value);
        hi = std::max(hi, c.value);
    }
    if (!(hi > lo)) {
        hi = lo + 1.0;
    }
    valueLo_ = lo;
    valueHi_ = hi;
}

QRectF TransferFunctionCanvas::opacityArea() const {
    return {kMargin, kMargin, width() - 2 * kMargin,
            std::max(1.0, height() - 2 * kMargin - kStripHeight - kStripGap)};
}

QRectF TransferFunctionCanvas::colourStrip() const {
    const QRectF area = opacityArea();
    return {area.left(), area.bottom() + kStripGap, area.width(), kStripHeight};
}

double TransferFunctionCanvas::xOfValue(double value) const {
    const QRectF area = opacityArea();
    return area.left() + (value - valueLo_) / (valueHi_ - valueLo_) * area.width();
}

double TransferFunctionCanvas::valueAtX(double x) const {
    const QRectF area = opacityArea();
    return valueLo_ + (x - area.left()) / area.width() * (valueHi_ - valueLo_);
}

double TransferFunctionCanvas::yOfOpacity(double opacity) const {
    const QRectF area = opacityArea();
    return area.bottom() - opacity * area.height();
}

double TransferFunctionCanvas::opacityAtY(double y) const {
    const QRectF area = opacityArea();
    return (area.bottom() - y) / area.height();
}

QPointF TransferFunctionCanvas::opacityPointPosition(int index) const {
    const auto& p = tf_.opacity.at(static_cast<std::size_t>(index));
    return {xOfValue(p.value), yOfOpacity(p.opacity)};
}

QPointF TransferFunctionCanvas::colourStopPosition(int index) const {
    return {xOfValue(tf_.colour.at(static_cast<std::size_t>(index)).value),
            colourStrip().center().y()};
}

int TransferFunctionCanvas::opacityPointAt(const QPointF& pos) const {
    int best = -1;
    double bestDistance = kHitRadius;
    for (int i = 0; i < static_cast<int>(tf_.opacity.size()); ++i) {
        const QPointF d = opacityPointPosition(i) - pos;
        const double distance = std::hypot(d.x(), d.y());
        if (distance <= bestDistance) {
            best = i;
            bestDistance = distance;
        }
    }
    return best;
}

int TransferFunctionCanvas::colourStopAt(const QPointF& pos) const {
    if (!colourStrip().adjusted(0, -4, 0, 4).contains(pos)) {
        return -1;
    }
    int best = -1;
    double bestDistance = kHitRadius;
    for (int i = 0; i < static_cast<int>(tf_.colour.size()); ++i) {
        const double distance = std::abs(colourStopPosition(i).x() - pos.x());
        if (distance <= bestDistance) {
            best = i;
            bestDistance = distance;
        }
    }
    return best;
}

template <class Points>
double TransferFunctionCanvas::clampBetweenNeighbours(const Points& points, int index,
                                                      double value) const {
    const double gap = (valueHi_ - valueLo_) * 1e-4;
    double lo = valueLo_, hi = valueHi_;
    if (index > 0) {
        lo = points[static_cast<std::size_t>(index - 1)].value + gap;
    }
    if (index + 1 < static_cast<int>(points.size())) {
        hi = points[static_cast<std::size_t>(index + 1)].value - gap;
    }
    return std::clamp(value, lo, std::max(lo, hi));
}

void TransferFunctionCanvas::changed() {
    update();
    emit transferFunctionChanged(tf_);
}

void TransferFunctionCanvas::mousePressEvent(QMouseEvent* event) {
    const QPointF pos = event->position();
    const int point = opacityPointAt(pos);
    const int stop = point < 0 ? colourStopAt(pos) : -1;
    if (event->button() == Qt::LeftButton) {
        if (point >= 0) {
            drag_ = Drag::OpacityPoint;
            dragIndex_ = point;
            selected_ = point;
            update();
        } else if (stop >= 0) {
            drag_ = Drag::ColourStop;
            dragIndex_ = stop;
        }
    } else if (event->button() == Qt::RightButton) {
        if (point >= 0) {
            removeOpacityPoint(point);
        } else if (stop >= 0 && tf_.colour.size() > 1) {
            tf_.colour.erase(tf_.colour.begin() + stop);
            changed();
        }
    }
}

void TransferFunctionCanvas::mouseMoveEvent(QMouseEvent* event) {
    const QPointF pos = event->position();
    if (drag_ == Drag::OpacityPoint) {
        auto& p = tf_.opacity[static_cast<std::size_t>(dragIndex_)];
        p.value = clampBetweenNeighbours(tf_.opacity, dragIndex_, valueAtX(pos.x()));
        p.opacity = std::clamp(opacityAtY(pos.y()), 0.0, 1.0);
        changed();
    } else if (drag_ == Drag::ColourStop) {
        auto& c = tf_.colour[static_cast<std::size_t>(dragIndex_)];
        c.value = clampBetweenNeighbours(tf_.colour, dragIndex_, valueAtX(pos.x()));
        changed();
    }
}

void TransferFunctionCanvas::mouseReleaseEvent(QMouseEvent* event) {
    if (event->button() == Qt::LeftButton) {
        drag_ = Drag::None;
        dragIndex_ = -1;
    }
}

void TransferFunctionCanvas::mouseDoubleClickEvent(QMouseEvent* event) {
    if (event->button() != Qt::LeftButton) {
        return;
    }
    drag_ = Drag::None;
    const QPointF pos = event->position();
    if (colourStrip().adjusted(0, -4, 0, 4).contains(pos)) {
        const int stop = colourStopAt(pos);
        if (stop >= 0) {
            editColourStop(stop);
        } else {
            addColourStop(valueAtX(pos.x()));
        }
    } else if (opacityArea().contains(pos) && opacityPointAt(pos) < 0) {
        addOpacityPoint(pos);
    }
}

void TransferFunctionCanvas::keyPressEvent(QKeyEvent* event) {
    if ((event->key() == Qt::Key_Delete || event->key() == Qt::Key_Backspace) && selected_ >= 0) {
        removeOpacityPoint(selected_);
        return;
    }
    QWidget::keyPressEvent(event);
}

void TransferFunctionCanvas::addOpacityPoint(const QPointF& pos) {
    const OpacityPoint p{valueAtX(pos.x()), std::clamp(opacityAtY(pos.y()), 0.0, 1.0)};
    const auto at =
        std::lower_bound(tf_.opacity.begin(), tf_.opacity.end(), p.value,
                         [](const OpacityPoint& a, double value) { return a.value < value; });
    if (at != tf_.opacity.end() && at->value == p.value) {
        return; // values must stay strictly increasing
    }
    const auto index = at - tf_.opacity.begin();
    tf_.opacity.insert(at, p);
    selected_ = static_cast<int>(index);
    changed();
}

void TransferFunctionCanvas::removeOpacityPoint(int index) {
    if (tf_.opacity.size() <= 1) {
        return;
    }
    tf_.opacity.erase(tf_.opacity.begin() + index);
    selected_ = -1;
    changed();
}

void TransferFunctionCanvas::editColourStop(int index) {
    auto& c = tf_.colour[static_cast<std::size_t>(index)];
    if (const auto picked = colourPicker_(toQColor(c.rgb))) {
        c.rgb = toRgb(*picked);
        changed();
    }
}

void TransferFunctionCanvas::addColourStop(double value) {
    const auto at = std::lower_bound(tf_.colour.begin(), tf_.colour.end(), value,
                                     [](const ColourPoint& a, double v) { return a.value < v; });
    if (at != tf_.colour.end() && at->value == value) {
        return;
    }
    const auto index = at - tf_.colour.begin();
    if (const auto picked = colourPicker_(toQColor(tf_.colourAt(value)))) {
        tf_.colour.insert(tf_.colour.begin() + index, ColourPoint{value, toRgb(*picked)});
        changed();
    }
}

void TransferFunctionCanvas::paintHistogram(QPainter& painter, const QRectF& area) const {
    const std::uint64_t largest = histogram_.largestCount();
    if (largest == 0) {
        return;
    }
    const double logLargest = std::log1p(static_cast<double>(largest));
    const double w = histogram_.binWidth();
    for (std::size_t n = 0; n < histogram_.counts.size(); ++n) {
        const double x0 = xOfValue(histogram_.lo + double(n) * w);
        const double x1 = xOfValue(histogram_.lo + double(n + 1) * w);
        const double h =
            std::log1p(static_cast<double>(histogram_.counts[n])) / logLargest * area.height();
        painter.fillRect(QRectF(x0, area.bottom() - h, std::max(1.0, x1 - x0), h),
                         QColor(90, 90, 100));
    }
}

void TransferFunctionCanvas::paintColourStrip(QPainter& painter, const QRectF& strip) const {
    for (int x = static_cast<int>(strip.left()); x < static_cast<int>(strip.right()); ++x) {
        painter.setPen(toQColor(tf_.colourAt(valueAtX(x + 0.5))));
        painter.drawLine(QPointF(x + 0.5, strip.top()), QPointF(x + 0.5, strip.bottom()));
    }
    for (int i = 0; i < static_cast<int>(tf_.colour.size()); ++i) {
        const QPointF c = colourStopPosition(i);
        painter.setPen(QPen(Qt::white, 1.5));
        painter.setBrush(toQColor(tf_.colour[static_cast<std::size_t>(i)].rgb));
        painter.drawRect(QRectF(c.x() - 4, strip.top() - 3, 8, strip.height() + 6));
    }
}

void TransferFunctionCanvas::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    // Around the plot the dock's own colour; the plot itself stays dark, like an image.
    painter.fillRect(rect(), palette().window());
    const QRectF area = opacityArea();
    painter.fillRect(area, QColor(20, 20, 22));
    paintHistogram(painter, area);
    painter.setRenderHint(QPainter::Antialiasing);

    QPainterPath curve;
    curve.moveTo(area.left(), yOfOpacity(tf_.opacity.empty() ? 0.0 : tf_.opacity.front().opacity));
    for (int i = 0; i < static_cast<int>(tf_.opacity.size()); ++i) {
        curve.lineTo(opacityPointPosition(i));
    }
    curve.lineTo(area.right(), yOfOpacity(tf_.opacity.empty() ? 0.0 : tf_.opacity.back().opacity));
    painter.setPen(QPen(QColor(230, 230, 230), 1.5));
    painter.drawPath(curve);
    for (int i = 0; i < static_cast<int>(tf_.opacity.size()); ++i) {
        const QPointF c = opacityPointPosition(i);
        painter.setPen(QPen(i == selected_ ? QColor(255, 200, 0) : Qt::white, 1.5));
        painter.setBrush(toQColor(tf_.colourAt(tf_.opacity[static_cast<std::size_t>(i)].value)));
        painter.drawEllipse(c, 5.0, 5.0);
    }
    paintColourStrip(painter, colourStrip());
}

} // namespace lucent
