#pragma once

#include <vector>

#include <QString>

#include <glm/glm.hpp>

#include "core/mpr/PlaneSampler.h"
#include "core/mpr/RoiStatistics.h"
#include "core/volume/Volume.h"

class QPainter;

namespace lucent {

// A straight line between two patient points (LPS mm).
struct DistanceMeasurement {
    glm::dvec3 start{0.0};
    glm::dvec3 end{0.0};
    double lengthMm() const { return glm::distance(start, end); }
};

// An ellipse drawn on a plane, with the statistics of the values inside it.
struct EllipseMeasurement {
    SlicePlane plane; // the plane it was drawn on (its u and v are the ellipse's axes)
    EllipseRoi ellipse;
    RoiStatistics statistics;
};

enum class MeasurementKind { Distance, Ellipse };

// The measurements of one MPR view, kept in patient coordinates, and the one being
// drawn: begin() at the first point, moveTo() while the mouse moves, finish() at the
// second point (a distance's other end, an ellipse's opposite bounding-box corner).
class SliceMeasurements {
public:
    bool drawing() const { return drawing_; }
    void begin(MeasurementKind kind, const glm::dvec3& point);
    void moveTo(const glm::dvec3& point);
    // Ends the measurement being drawn at `point`; an ellipse takes its statistics
    // from the volume resliced on `plane`.
    void finish(const glm::dvec3& point, const Volume& volume, const SlicePlane& plane);
    void cancel() { drawing_ = false; }
    void clear();

    const std::vector<DistanceMeasurement>& distances() const { return distances_; }
    const std::vector<EllipseMeasurement>& ellipses() const { return ellipses_; }

    // Draws the measurements that lie in `plane` (within `tolerance` mm along its
    // normal) and the one being drawn; `unit` follows the ROI values ("HU" for CT).
    void paint(QPainter& painter, const SlicePlane& plane, double tolerance,
               const QString& unit) const;

private:
    static EllipseRoi ellipseBetween(const glm::dvec3& a, const glm::dvec3& b,
                                     const SlicePlane& plane);

    bool drawing_ = false;
    MeasurementKind kind_ = MeasurementKind::Distance;
    glm::dvec3 first_{0.0};
    glm::dvec3 current_{0.0};
    std::vector<DistanceMeasurement> distances_;
    std::vector<EllipseMeasurement> ellipses_;
};

} // namespace lucent
