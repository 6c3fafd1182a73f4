#pragma once
// The voxels a GPU brick holds, copied out of a volume without any GL: a box
// of values, and a box of their gradients for the gradient cache. The GPU
// brick pool uploads what these give; the tests check them on their own.

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include <glm/glm.hpp>

namespace lucent {

// Not even the coarsest level's needed bricks fit the budget.
class BudgetError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Beyond the volume's edge a box repeats the edge voxel (what trilinear
// sampling clamps to) or mirrors about it (the B-spline coefficients' boundary).
enum class BrickEdge { Clamp, Mirror };

// Copies the voxels [lo, lo + size) of a volume of `dims` into out (x
// fastest); indices outside the volume follow `edge`. T: int16_t, uint16_t or float.
template <class T>
void extractBox(const T* data, glm::ivec3 dims, glm::ivec3 lo, glm::ivec3 size, BrickEdge edge,
                T* out);

// The gradient over the same box: half the difference of the two neighbours
// along each axis (indices clamped to the volume), divided by `unit` and
// rounded to int16, four per voxel (x, y, z, 0). Trilinear interpolation of
// these gives the central differences of the trilinear field one voxel apart
// (what the ray casters shade with), up to rounding, except on the outermost
// voxels. unit = (max - min) / 2 / 32767 keeps every component in range.
template <class T>
void extractGradientBox(const T* data, glm::ivec3 dims, glm::ivec3 lo, glm::ivec3 size, double unit,
                        std::int16_t* out);

} // namespace lucent
