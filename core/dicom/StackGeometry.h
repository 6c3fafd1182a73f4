#pragma once

#include <string>
#include <vector>

#include "core/volume/Volume.h"

namespace lucent {

// A stack of 2D images of one orientation and size, as the headers describe it.
struct StackInput {
    std::vector<glm::dvec3> positions; // ImagePositionPatient of each image
    glm::dvec3 rowDir{1.0, 0.0, 0.0};  // i axis of every image
    glm::dvec3 colDir{0.0, 1.0, 0.0};  // j axis of every image
    glm::dvec2 pixelSpacing{1.0};      // along i, along j
    int columns = 0;
    int rows = 0;
    double sliceThickness = 0.0; // only for a single image
};

// Keeping the acquired grid puts each slice where an even stack along the
// normal would have it. Within these tolerances that error is smaller than
// what resampling costs (a second interpolation that blurs every voxel), so
// the grid is kept with a warning; beyond them the stack is resampled.
// In plane: every slice within a quarter pixel of the first slice's lattice.
inline constexpr double kShiftTolerancePixels = 0.25;
// Along the normal: every slice within 5 % of the mean gap of its even place.
inline constexpr double kGridTolerance = 0.05;

// How the stack becomes a volume. Images at the same position are dropped;
// the others are ordered along the normal (row x column). When the stack is
// tilted (position steps not along the normal) or its gaps are uneven beyond
// the tolerances above, the geometry is a rectilinear grid along the normal
// that covers every image, and each kept image has its place in that grid
// for resampling.
struct StackPlan {
    std::vector<int> order;   // input indices kept, ascending along the normal
    std::vector<int> dropped; // input indices at a position already taken
    VolumeGeometry geometry;
    bool resample = false;
    // Per kept image: the grid index coordinates of its pixel (0, 0).
    std::vector<glm::dvec3> placement;
    double tiltDegrees = 0.0;
    double shiftPixels = 0.0;   // largest in-plane offset of a slice from the first, in pixels
    double gridDeviation = 0.0; // largest distance of a slice from its even place, in mean gaps
    bool unevenGaps = false;    // beyond kGridTolerance: resampled along the normal
    int missingSlices = 0;
    std::vector<std::string> warnings;
    // Non-empty when the images cannot form one volume (they share one plane).
    std::string error;
};

StackPlan planStack(const StackInput& input);

} // namespace lucent
