#pragma once
// Curved planar reformation (Kanitsar et al., "CPR - Curved Planar
// Reformation", IEEE Visualization 2002) along a path clicked through a
// vessel, the mandible or the spine. Plain C++ and GLM.
//
// Straightened: each image row is a cross-section line of the path at equal
// arc-length steps, so the path becomes the image's vertical centre line and
// lengths along it are true. Stretched: the surface swept by lines parallel
// to an "up" vector through the path, unrolled without distortion (it is
// developable): rows at equal arc length of the path seen along up, columns
// the height along up, so the path keeps its shape across and distances on
// the surface are true in both directions.

#include <vector>

#include <glm/glm.hpp>

#include "core/mpr/PlaneSampler.h"
#include "core/volume/Volume.h"

namespace lucent {

// A path sampled at equal arc-length steps: position, unit tangent and a
// rotation-minimizing normal (double reflection, Wang et al. 2008), so the
// cross-section frame does not twist around a curving path.
struct Centerline {
    std::vector<glm::dvec3> points;
    std::vector<glm::dvec3> tangents;
    std::vector<glm::dvec3> normals; // unit, perpendicular to the tangent
    double step = 0.0;               // mm between points
    double length() const { return points.empty() ? 0.0 : step * double(points.size() - 1); }
    // The frame at arc length s (mm, clamped to the path): linear between samples.
    glm::dvec3 pointAt(double s) const;
    glm::dvec3 tangentAt(double s) const;
    glm::dvec3 normalAt(double s) const;
};

// A centripetal Catmull-Rom spline through the control points (no cusps or
// self-intersections between close points), sampled every `step` mm. The
// first normal is the component of `up` perpendicular to the first tangent
// (any perpendicular when up is along it). Needs two or more distinct points.
Centerline centerlineThrough(const std::vector<glm::dvec3>& controls, double step,
                             const glm::dvec3& up = {0.0, 0.0, 1.0});

struct CurvedImage {
    int width = 0;
    int height = 0;
    double pixelSize = 1.0;    // mm, both directions
    std::vector<float> pixels; // row-major; NaN outside the volume
    // Per row: the patient point of column 0 and the unit step along the row,
    // so pixel (x, y) lies at rowOrigin[y] + rowDirection[y] * x * pixelSize.
    std::vector<glm::dvec3> rowOrigin;
    std::vector<glm::dvec3> rowDirection;
    std::vector<double> pathColumn; // per row: the column where the path crosses it
    std::vector<double> rowArc;     // per row: arc length (mm) along the path
    glm::dvec3 pointAt(double x, int y) const {
        return rowOrigin[y] + rowDirection[y] * (x * pixelSize);
    }
};

struct CurvedOptions {
    double pixelSize = 0.5;     // mm
    double halfWidth = 30.0;    // mm across the path on each side (straightened)
    double rotationDeg = 0.0;   // straightened: the cut plane's turn around the path
    double slabThickness = 0.0; // mm; > 0 combines samples across the cut surface
    SlabMode slabMode = SlabMode::Mip;
};

// The straightened reformation: row y at arc length y * pixelSize, column x at
// (x - width/2) * pixelSize along the path's normal turned by rotationDeg.
CurvedImage straightenedReformat(const Volume& volume, const Centerline& path,
                                 const CurvedOptions& options);

// The stretched reformation along `up` (e.g. the normal of the MPR view the
// path was drawn on); columns cover the path's extent along up plus
// options.halfWidth on each side.
CurvedImage stretchedReformat(const Volume& volume, const Centerline& path, const glm::dvec3& up,
                              const CurvedOptions& options);

// The plane across the path at arc length s: u the path's normal, v its
// binormal, centred on the path, size x size pixels.
SlicePlane crossSection(const Centerline& path, double s, int size, double pixelSize);

} // namespace lucent
