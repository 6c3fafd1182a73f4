#include "core/measure/MeasurementGeometry.h"

#include <cmath>

namespace lucent {

namespace {

glm::dvec3 unitNormal(const SlicePlane& plane) {
    const glm::dvec3 n = plane.normal();
    const double length = glm::length(n);
    return length > 0.0 ? n / length : glm::dvec3(0.0, 0.0, 1.0);
}

glm::dvec3 projected(const SlicePlane& plane, const glm::dvec3& p) {
    const glm::dvec3 n = unitNormal(plane);
    return p - n * glm::dot(p - plane.centre, n);
}

// The in-plane unit vector perpendicular to a-b (along plane.u when a == b).
glm::dvec3 perpendicular(const SlicePlane& plane, const glm::dvec3& a, const glm::dvec3& b) {
    const glm::dvec3 along = b - a;
    const double length = glm::length(along);
    if (length <= 0.0) {
        return glm::normalize(plane.v);
    }
    return glm::normalize(glm::cross(unitNormal(plane), along / length));
}

void moveBidirectional(Measurement& m, int index, const glm::dvec3& to) {
    std::vector<glm::dvec3>& p = m.points;
    const glm::dvec3 axis = p[1] - p[0];
    const double length2 = glm::dot(axis, axis);
    const glm::dvec3 w = perpendicular(m.plane, p[0], p[1]);
    // Where the short axis crosses the long one, as a fraction of it.
    const glm::dvec3 shortMid = 0.5 * (p[2] + p[3]);
    const double t = length2 > 0.0 ? glm::dot(shortMid - p[0], axis) / length2 : 0.5;
    const glm::dvec3 crossing = p[0] + t * axis;
    if (index >= 2) {
        p[static_cast<std::size_t>(index)] = crossing + w * glm::dot(to - crossing, w);
        return;
    }
    const double s2 = glm::dot(p[2] - crossing, w);
    const double s3 = glm::dot(p[3] - crossing, w);
    p[static_cast<std::size_t>(index)] = to;
    const glm::dvec3 w2 = perpendicular(m.plane, p[0], p[1]);
    const glm::dvec3 c2 = p[0] + t * (p[1] - p[0]);
    p[2] = c2 + s2 * w2;
    p[3] = c2 + s3 * w2;
}

} // namespace

Measurement makeBidirectionalMeasurement(const SlicePlane& plane, const glm::dvec3& a,
                                         const glm::dvec3& b, double shortRatio) {
    Measurement m;
    m.kind = MeasurementKind::Bidirectional;
    m.plane = plane;
    const glm::dvec3 pa = projected(plane, a);
    const glm::dvec3 pb = projected(plane, b);
    const glm::dvec3 w = perpendicular(plane, pa, pb);
    const double half = 0.5 * shortRatio * glm::distance(pa, pb);
    const glm::dvec3 mid = 0.5 * (pa + pb);
    m.points = {pa, pb, mid - half * w, mid + half * w};
    return m;
}

Measurement makeEllipseFromCorners(const SlicePlane& plane, const glm::dvec3& a,
                                   const glm::dvec3& b) {
    EllipseRoi e;
    e.centre = projected(plane, 0.5 * (a + b));
    e.radiusU = 0.5 * std::abs(glm::dot(b - a, glm::normalize(plane.u)));
    e.radiusV = 0.5 * std::abs(glm::dot(b - a, glm::normalize(plane.v)));
    return makeEllipseMeasurement(plane, e);
}

bool moveMeasurementPoint(Measurement& m, int index, const glm::dvec3& to) {
    if (index < 0 || index >= static_cast<int>(m.points.size())) {
        return false;
    }
    const glm::dvec3 target = projected(m.plane, to);
    if (m.kind == MeasurementKind::Bidirectional && m.complete()) {
        moveBidirectional(m, index, target);
    } else if (m.kind == MeasurementKind::Ellipse && m.complete()) {
        EllipseRoi e = measurementEllipse(m);
        const double r = std::abs(
            glm::dot(target - e.centre, glm::normalize(index < 2 ? m.plane.u : m.plane.v)));
        (index < 2 ? e.radiusU : e.radiusV) = r;
        const Measurement moved = makeEllipseMeasurement(m.plane, e);
        m.points = moved.points;
    } else {
        m.points[static_cast<std::size_t>(index)] = target;
    }
    return true;
}

} // namespace lucent
