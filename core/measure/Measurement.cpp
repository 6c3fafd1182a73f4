#include "core/measure/Measurement.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace lucent {

namespace {

double degreesBetween(const glm::dvec3& a, const glm::dvec3& b) {
    const double la = glm::length(a);
    const double lb = glm::length(b);
    if (la <= 0.0 || lb <= 0.0) {
        return 0.0;
    }
    // atan2 of |a x b| and a . b stays accurate near 0 and 180 degrees, where acos does not.
    const double rad = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
    return rad * 180.0 / std::numbers::pi;
}

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0, double d = 0.0) {
    char buffer[160];
    std::snprintf(buffer, sizeof buffer, pattern, a, b, c, d);
    return buffer;
}

} // namespace

const char* measurementKindName(MeasurementKind kind) {
    switch (kind) {
    case MeasurementKind::Distance:
        return "Distance";
    case MeasurementKind::Angle:
        return "Angle";
    case MeasurementKind::CobbAngle:
        return "Cobb angle";
    case MeasurementKind::Arrow:
        return "Arrow";
    case MeasurementKind::Bidirectional:
        return "Bidirectional";
    case MeasurementKind::Ellipse:
        return "Ellipse";
    }
    return "Measurement";
}

const char* lesionRoleName(LesionRole role) {
    switch (role) {
    case LesionRole::None:
        return "";
    case LesionRole::Target:
        return "Target";
    case LesionRole::NonTarget:
        return "Non-target";
    }
    return "";
}

int measurementPointCount(MeasurementKind kind) {
    switch (kind) {
    case MeasurementKind::Distance:
    case MeasurementKind::Arrow:
        return 2;
    case MeasurementKind::Angle:
        return 3;
    case MeasurementKind::CobbAngle:
    case MeasurementKind::Bidirectional:
    case MeasurementKind::Ellipse:
        return 4;
    }
    return 0;
}

double measurementLengthMm(const Measurement& m) {
    return m.points.size() >= 2 ? glm::distance(m.points[0], m.points[1]) : 0.0;
}

double measurementAngleDegrees(const Measurement& m) {
    if (m.kind == MeasurementKind::Angle && m.points.size() == 3) {
        return degreesBetween(m.points[0] - m.points[1], m.points[2] - m.points[1]);
    }
    if (m.kind == MeasurementKind::CobbAngle && m.points.size() == 4) {
        const double a = degreesBetween(m.points[1] - m.points[0], m.points[3] - m.points[2]);
        return std::min(a, 180.0 - a); // lines, not rays: the acute angle between them
    }
    return 0.0;
}

double bidirectionalLongAxisMm(const Measurement& m) {
    return m.points.size() == 4 ? glm::distance(m.points[0], m.points[1]) : 0.0;
}

double bidirectionalShortAxisMm(const Measurement& m) {
    return m.points.size() == 4 ? glm::distance(m.points[2], m.points[3]) : 0.0;
}

EllipseRoi measurementEllipse(const Measurement& m) {
    EllipseRoi e;
    if (m.points.size() != 4) {
        return e;
    }
    e.centre = 0.25 * (m.points[0] + m.points[1] + m.points[2] + m.points[3]);
    e.radiusU = 0.5 * glm::distance(m.points[0], m.points[1]);
    e.radiusV = 0.5 * glm::distance(m.points[2], m.points[3]);
    return e;
}

Measurement makeEllipseMeasurement(const SlicePlane& plane, const EllipseRoi& ellipse) {
    Measurement m;
    m.kind = MeasurementKind::Ellipse;
    m.plane = plane;
    const glm::dvec3 du = ellipse.radiusU * plane.u;
    const glm::dvec3 dv = ellipse.radiusV * plane.v;
    m.points = {ellipse.centre - du, ellipse.centre + du, ellipse.centre - dv, ellipse.centre + dv};
    return m;
}

std::string measurementValueText(const Measurement& m) {
    switch (m.kind) {
    case MeasurementKind::Distance:
        return format("%.1f mm", measurementLengthMm(m));
    case MeasurementKind::Angle:
    case MeasurementKind::CobbAngle:
        return format("%.1f\u00b0", measurementAngleDegrees(m));
    case MeasurementKind::Arrow:
        return m.text;
    case MeasurementKind::Bidirectional:
        return format("%.1f x %.1f mm", bidirectionalLongAxisMm(m), bidirectionalShortAxisMm(m));
    case MeasurementKind::Ellipse: {
        const RoiStatistics& s = m.statistics;
        std::string unit = m.unit.empty() ? std::string() : " " + m.unit;
        const std::string suv = m.suv ? format("SUVmax %.2f SUVpeak %.2f SUVmean %.2f ", m.suv->max,
                                               m.suv->peak, m.suv->mean)
                                      : std::string();
        return suv + format("Mean %.1f", s.mean) + unit +
               format(" SD %.1f Area %.1f mm\u00b2", s.standardDeviation, s.areaMm2);
    }
    }
    return {};
}

std::string measurementUnit(const Volume& volume) {
    if (volume.pet) {
        return volume.pet->unit();
    }
    return volume.modality == "CT" ? "HU" : "";
}

std::optional<SuvStatistics> measurementSuv(const Volume& volume, const Measurement& m) {
    if (m.kind != MeasurementKind::Ellipse || !m.complete() || !volume.pet ||
        !volume.pet->inSuv() || volume.empty()) {
        return std::nullopt;
    }
    const std::vector<glm::ivec3> region =
        ellipseSuvRegion(volume.geometry(), m.plane, measurementEllipse(m));
    return suvStatistics(volume, region);
}

double distanceFromPlane(const Measurement& m, const SlicePlane& plane) {
    double largest = 0.0;
    for (const glm::dvec3& p : m.points) {
        largest = std::max(largest, std::abs(plane.distance(p)));
    }
    return largest;
}

} // namespace lucent
