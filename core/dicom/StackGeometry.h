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

// How the stack becomes a volume. Images at the same position are dropped;
// the others are ordered along the normal (row x column). When the stack is
// tilted (position steps not along the normal) or its gaps are uneven, the
// geometry is a rectilinear grid along the normal that covers every image,
// and each kept image has its place in that grid for resampling.
struct StackPlan {
    std::vector<int> order;   // input indices kept, ascending along the normal
    std::vector<int> dropped; // input indices at a position already taken
    VolumeGeometry geometry;
    bool resample = false;
    // Per kept image: the grid index coordinates of its pixel (0, 0).
    std::vector<glm::dvec3> placement;
    double tiltDegrees = 0.0;
    bool unevenGaps = false;
    int missingSlices = 0;
    std::vector<std::string> warnings;
    // Non-empty when the images cannot form one volume (they share one plane).
    std::string error;
};

StackPlan planStack(const StackInput& input);

} // namespace lucent
