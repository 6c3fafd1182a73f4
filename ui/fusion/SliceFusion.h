#pragma once
// An MPR view's fused overlay: a second series drawn over the view's own, resampled
// through the base -> overlay transform (core/fusion), with its colour bar, the swipe
// line and the overlay's statistics in the view's ellipse ROIs.

#include <memory>
#include <optional>
#include <vector>

#include <QImage>
#include <QString>

#include <glm/glm.hpp>

#include "core/fusion/FusionStyle.h"
#include "core/measure/Measurement.h"
#include "core/mpr/PlaneSampler.h"
#include "core/volume/Volume.h"

class QPainter;
class QRect;

namespace lucent {

// What a view fuses: the overlay, where it is, and how it is drawn.
struct FusionLayer {
    std::shared_ptr<const Volume> overlay;
    glm::dmat4 baseToOverlay{1.0}; // base LPS mm -> overlay LPS mm
    FusionStyle style;
    QString title; // names the overlay in the corner ("PT WB 2024-03-01")
    QString unit;  // of its values: "HU", "SUVbw", "" when unknown
};

class SliceFusion {
public:
    bool active() const { return layer_.has_value() && layer_->overlay != nullptr; }
    const std::optional<FusionLayer>& layer() const { return layer_; }
    void setLayer(std::optional<FusionLayer> layer);
    // Another look for the same overlay (the resampled values are kept).
    void setStyle(const FusionStyle& style);

    // The view's grey image (at devicePlane's pixels) with the overlay fused over it, as
    // RGB32 with the grey image's device pixel ratio. The grey image itself when inactive.
    QImage apply(const QImage& grey, const SlicePlane& devicePlane);
    // The overlay's value at a device pixel of the last apply(); NaN where it has none.
    double valueAt(int x, int y) const;

    // Over the view (logical pixels of `plane`): the colour bar with the window's values
    // and the unit at the right edge, the overlay's name, the swipe line, and the
    // overlay's mean and maximum under each ellipse within `tolerance` mm of the plane.
    void paint(QPainter& painter, const QRect& rect, const SlicePlane& plane,
               const std::vector<Measurement>& measurements, double tolerance) const;

private:
    std::optional<FusionLayer> layer_;
    std::vector<float> samples_; // the overlay at sampledPlane_'s pixels
    SlicePlane sampledPlane_;
    bool samplesValid_ = false;
    QImage fused_;
    qint64 fusedFrom_ = 0; // the grey image's cacheKey
    bool fusedValid_ = false;
};

} // namespace lucent
