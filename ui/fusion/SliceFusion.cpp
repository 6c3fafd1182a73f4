#include "ui/fusion/SliceFusion.h"

#include <cmath>

#include <QPainter>

#include "core/fusion/FusionCompositor.h"
#include "core/fusion/OverlayResampler.h"
#include "ui/fusion/FusionColourBar.h"

namespace lucent {
namespace {

bool samePlane(const SlicePlane& a, const SlicePlane& b) {
    return a.centre == b.centre && a.u == b.u && a.v == b.v && a.pixelSize == b.pixelSize &&
           a.width == b.width && a.height == b.height && a.slabThickness == b.slabThickness &&
           a.slabMode == b.slabMode;
}

QString statisticsText(const RoiStatistics& stats, const QString& unit) {
    const QString u = unit.isEmpty() ? QString() : QStringLiteral(" ") + unit;
    return QStringLiteral("Overlay mean %1 max %2%3")
        .arg(colourBarLabel(stats.mean), colourBarLabel(stats.maximum), u);
}

} // namespace

void SliceFusion::setLayer(std::optional<FusionLayer> layer) {
    layer_ = std::move(layer);
    samplesValid_ = false;
    fusedValid_ = false;
    samples_.clear();
}

void SliceFusion::setStyle(const FusionStyle& style) {
    if (layer_) {
        layer_->style = style;
        fusedValid_ = false;
    }
}

QImage SliceFusion::apply(const QImage& grey, const SlicePlane& devicePlane) {
    if (!active() || grey.isNull()) {
        return grey;
    }
    if (!samplesValid_ || !samePlane(devicePlane, sampledPlane_)) {
        samples_ = sampleOverlay(*layer_->overlay, devicePlane, layer_->baseToOverlay);
        sampledPlane_ = devicePlane;
        samplesValid_ = true;
        fusedValid_ = false;
    }
    if (fusedValid_ && fusedFrom_ == grey.cacheKey()) {
        return fused_;
    }
    const int w = devicePlane.width;
    const int h = devicePlane.height;
    std::vector<std::uint8_t> greyPixels(static_cast<std::size_t>(w) * h);
    for (int y = 0; y < h; ++y) {
        std::copy_n(grey.constScanLine(y), w, greyPixels.data() + static_cast<std::size_t>(y) * w);
    }
    const std::vector<Rgb32> fused =
        composeFusion(greyToRgb32(greyPixels), samples_, w, h, layer_->style);
    fused_ = QImage(w, h, QImage::Format_RGB32);
    for (int y = 0; y < h; ++y) {
        std::copy_n(fused.data() + static_cast<std::size_t>(y) * w, w,
                    reinterpret_cast<Rgb32*>(fused_.scanLine(y)));
    }
    fused_.setDevicePixelRatio(grey.devicePixelRatio());
    fusedFrom_ = grey.cacheKey();
    fusedValid_ = true;
    return fused_;
}

double SliceFusion::valueAt(int x, int y) const {
    if (!samplesValid_ || x < 0 || y < 0 || x >= sampledPlane_.width || y >= sampledPlane_.height) {
        return std::nan("");
    }
    return samples_[static_cast<std::size_t>(y) * sampledPlane_.width + x];
}

void SliceFusion::paint(QPainter& painter, const QRect& rect, const SlicePlane& plane,
                        const std::vector<Measurement>& measurements, double tolerance) const {
    if (!active()) {
        return;
    }
    const FusionStyle& style = layer_->style;
    painter.save();
    if (style.mode == FusionMode::Swipe) {
        const int x = rect.left() + static_cast<int>(std::lround(style.swipe * rect.width()));
        painter.setPen(QPen(QColor(255, 255, 0), 1, Qt::DashLine));
        painter.drawLine(x, rect.top(), x, rect.bottom());
    }
    const int barHeight = std::min(rect.height() / 2, 240);
    const QRect barArea(rect.right() - 90, rect.center().y() - barHeight / 2, 84, barHeight);
    paintFusionColourBar(painter, barArea, style, layer_->unit);
    painter.setPen(QColor(255, 200, 120));
    const QString name =
        QStringLiteral("Over: %1 (%2, %3)")
            .arg(layer_->title, QString::fromLatin1(colourMapTitle(style.colourMap)),
                 QString::fromLatin1(fusionModeName(style.mode)));
    painter.drawText(barArea.left() - 200, barArea.top() - 22, 290, 18,
                     Qt::AlignRight | Qt::AlignVCenter, name);
    for (const Measurement& m : measurements) {
        if (m.kind != MeasurementKind::Ellipse || !m.complete()) {
            continue;
        }
        const EllipseRoi roi = measurementEllipse(m);
        if (std::abs(plane.distance(roi.centre)) > tolerance) {
            continue;
        }
        const RoiStatistics stats =
            overlayEllipseStatistics(*layer_->overlay, m.plane, roi, layer_->baseToOverlay);
        if (stats.samples == 0) {
            continue;
        }
        const glm::dvec2 at = plane.pixelOf(roi.centre);
        const double below = std::max(roi.radiusU, roi.radiusV) / plane.pixelSize;
        painter.drawText(QPointF(at.x - 60.0, at.y + below + 30.0),
                         statisticsText(stats, layer_->unit));
    }
    painter.restore();
}

} // namespace lucent
