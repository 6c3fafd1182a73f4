#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/volume/Volume.h"

namespace lucent {

enum class Orientation { Axial, Coronal, Sagittal };
const char* orientationName(Orientation orientation);

// How the samples across a thick slab are combined into one pixel.
enum class SlabMode { Mip, MinIp, Average };

// A planar image through a volume, in LPS millimetres. u is the screen-right
// axis and v the screen-down axis (both unit, orthogonal); the viewer looks
// along normal() = u x v. Pixel (x, y) (x, y counted from 0, pixel centres at
// whole numbers) lies at pointAt(x, y); the image centre lies at `centre`.
struct SlicePlane {
    glm::dvec3 centre{0.0};
    glm::dvec3 u{1.0, 0.0, 0.0};
    glm::dvec3 v{0.0, 1.0, 0.0};
    double pixelSize = 1.0; // mm
    int width = 0;
    int height = 0;
    double slabThickness = 0.0; // mm; 0 means a thin slice
    SlabMode slabMode = SlabMode::Mip;

    glm::dvec3 normal() const { return glm::cross(u, v); }
    glm::dvec3 pointAt(double x, double y) const;
    // The pixel coordinates of the projection of p onto the plane.
    glm::dvec2 pixelOf(const glm::dvec3& p) const;
    // Signed distance of p from the plane along normal().
    double distance(const glm::dvec3& p) const { return glm::dot(p - centre, normal()); }
};

// The radiological view of the patient for an orientation, through `centre`:
// axial seen from the feet (right = +x Left, down = +y Posterior), coronal seen
// from the front (right = +x Left, down = -z Inferior), sagittal seen from the
// patient's left (right = +y Posterior, down = -z Inferior). The pixel size fits
// the whole volume into width x height pixels (see fitPixelSize).
SlicePlane standardPlane(const VolumeGeometry& geometry, Orientation orientation,
                         const glm::dvec3& centre, int width = 0, int height = 0);

// Pixel size (mm) that fits the volume's box (the outer faces of its border voxels),
// projected on the plane's u and v axes, into width x height pixels. Without a
// size, or for a volume with no extent, it is the smallest spacing.
double fitPixelSize(const VolumeGeometry& geometry, const glm::dvec3& u, const glm::dvec3& v,
                    int width, int height);

// The distance along `normal` that moves one voxel: the step after which the index
// along the volume axis most aligned with the normal has changed by one. For an
// axis-aligned normal it is that axis's spacing.
double sliceStep(const VolumeGeometry& geometry, const glm::dvec3& normal);

// Trilinear interpolation at a continuous index; points within half a voxel of the
// outermost voxel centres take the border value, points further out return `fill`.
double sampleAt(const Volume& volume, const glm::dvec3& ijk,
                double fill = std::numeric_limits<double>::quiet_NaN());

// The plane's pixels, row-major (width * height), trilinearly interpolated in the
// volume's index space. A thick slab combines samples spaced at most one voxel step
// (sliceStep) apart from -thickness/2 to +thickness/2 along the normal, both ends
// included; samples outside the volume are left out, and a pixel with none inside
// is `fill`.
std::vector<float> sampleImage(const Volume& volume, const SlicePlane& plane,
                               float fill = std::numeric_limits<float>::quiet_NaN());

// Window/level to 8-bit grey: center - width/2 maps to 0, center + width/2 to 255.
// NaN maps to 0. A width of (nearly) zero thresholds at center.
std::uint8_t windowToGrey(double value, double center, double width);

struct WindowLevel {
    double center = 40.0;
    double width = 400.0;
    double step = 1.0; // what one pixel of mouse drag changes
};

// A starting window for a volume: soft tissue (L 40, W 400, 1 HU per pixel) for CT,
// 0 to 6 SUV for PET shown in SUVbw (core/pet/PetDisplay.h), otherwise the 1st to 99th
// percentile of its values (from at most about a million of them) with a step of a
// thousandth of that width.
WindowLevel defaultWindow(const Volume& volume);

// The patient direction letters of a vector (L/R, P/A, S/I), strongest component
// first; components weaker than a quarter of the strongest are left out.
// Example: (1, 0, 0) -> "L", (0, -0.7, 0.7) -> "AS" or "SA".
std::string directionLabel(const glm::dvec3& direction);

} // namespace lucent
