#include "ui/mpr/MeasurementNavigation.h"

#include <array>
#include <cmath>

#include "ui/mpr/MprCursor.h"

namespace lucent {

namespace {

constexpr double kParallel = 0.9999; // |cos| of planes taken as parallel (0.8 degrees)
constexpr std::array<Orientation, 3> kOrientations{Orientation::Axial, Orientation::Coronal,
                                                   Orientation::Sagittal};

glm::dvec3 unitNormal(const SlicePlane& plane) {
    return glm::normalize(plane.normal());
}

// The columns: a plane's right, down and normal unit vectors.
glm::dmat3 frameOf(const glm::dvec3& u, const glm::dvec3& v) {
    const glm::dvec3 nu = glm::normalize(u);
    const glm::dvec3 nv = glm::normalize(v);
    return {nu, nv, glm::cross(nu, nv)};
}

} // namespace

glm::dvec3 measurementCentre(const Measurement& m) {
    glm::dvec3 sum(0.0);
    for (const glm::dvec3& p : m.points) {
        sum += p;
    }
    return m.points.empty() ? sum : sum / static_cast<double>(m.points.size());
}

QString measurementPlaneName(const Measurement& m) {
    const glm::dvec3 n = glm::abs(unitNormal(m.plane));
    if (n.z > kParallel) {
        return QStringLiteral("Axial");
    }
    if (n.y > kParallel) {
        return QStringLiteral("Coronal");
    }
    if (n.x > kParallel) {
        return QStringLiteral("Sagittal");
    }
    return QStringLiteral("Oblique");
}

std::optional<int> measurementSlice(const Measurement& m, const VolumeGeometry& geometry) {
    const glm::dvec3 n = unitNormal(m.plane);
    for (int a = 0; a < 3; ++a) {
        if (std::abs(glm::dot(glm::dvec3(geometry.direction[a]), n)) > 0.999) {
            return static_cast<int>(std::lround(geometry.toIndex(measurementCentre(m))[a])) + 1;
        }
    }
    return std::nullopt;
}

void showMeasurement(MprCursor& cursor, const Measurement& m) {
    const glm::dvec3 n = unitNormal(m.plane);
    bool shown = false;
    for (const Orientation o : kOrientations) {
        shown = shown || std::abs(glm::dot(glm::normalize(cursor.planeNormal(o)), n)) > kParallel;
    }
    if (!shown) {
        // The standard orientation nearest m's plane, turned onto it: R maps its axes to m's.
        const glm::dvec3 p = cursor.point();
        Orientation nearest = Orientation::Axial;
        double best = -1.0;
        for (const Orientation o : kOrientations) {
            const SlicePlane standard = standardPlane({}, o, p);
            const double c = std::abs(glm::dot(unitNormal(standard), n));
            if (c > best) {
                best = c;
                nearest = o;
            }
        }
        const SlicePlane base = standardPlane({}, nearest, p);
        const glm::dmat3 turn =
            frameOf(m.plane.u, m.plane.v) * glm::transpose(frameOf(base.u, base.v));
        // Every plane turns with it, keeping the three perpendicular; a plane that the turn
        // leaves where it was (turned about its own normal) stays upright instead.
        for (const Orientation o : kOrientations) {
            const glm::dvec3 n0 = unitNormal(standardPlane({}, o, p));
            const bool keeps = std::abs(glm::dot(turn * n0, n0)) > 1.0 - 1e-9;
            cursor.setRotation(o, keeps && o != nearest ? glm::dmat3(1.0) : turn);
        }
    }
    cursor.setPoint(measurementCentre(m));
}

} // namespace lucent
