#pragma once
// The scene of the render benchmarks (issue 31) and what they share to set it up: the VTK
// anchor's opacity unit, the converged reference, volumes tiled beyond a CT's size, the median.

#include <vector>

#include <glm/glm.hpp>

#include "core/scene/RenderDescription.h"
#include "core/tf/TransferFunction.h"
#include "core/volume/Volume.h"

namespace lucent::bench {

// A transfer function whose opacities are per unitMm (VTK's unit distance is
// 1 mm) rewritten per dt_ref, Lucent's unit: a' = 1 - (1 - a)^(dt_ref / unit).
// unitMm <= 0 leaves it as it is.
TransferFunction opacityPerUnit(TransferFunction tf, const Volume& volume, double unitMm);

// The benchmarks' scene: `volume` with ct-bone (opacities per unitMm when > 0, else per voxel
// of the smallest spacing), shading, trilinear, step 0.5 voxel, Lucent's anterior camera,
// width x height.
RenderDescription ctBoneScene(const Volume& volume, double unitMm, int width = 512,
                              int height = 512);

// What every benchmark measures accuracy against: `d` tricubic, step 1/16 voxel, double.
RenderDescription converged(const RenderDescription& d);

// `ct` repeated to `dims` in mirrored tiles (no seams): the volumes beyond a GPU's memory
// (512 x 512 x 5382, 1024^3) and the 512^3 cube, made from a real CT.
Volume tiled(const Volume& ct, glm::ivec3 dims);

double median(std::vector<double> v);

} // namespace lucent::bench
