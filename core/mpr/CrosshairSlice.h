#pragma once
// The slice a linked MPR view shows through the crosshair point, and its grey
// image: one home for the workstation's SliceView and the render server's
// browser slices, so that both show the same pixels for the same plane and window.

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "core/mpr/PlaneSampler.h"
#include "core/volume/Volume.h"

namespace lucent {

// The orientation's standard plane fitted to width x height at zoom 1 (the
// unturned plane's fit: turning a plane does not zoom it), turned by `rotation`,
// through `crosshair` along its normal and centred on the volume's centre plus
// `pan` (mm along u and v); `zoom` divides the pixel size. A geometry without
// voxels centres it on the crosshair.
SlicePlane crosshairPlane(const VolumeGeometry& geometry, Orientation orientation,
                          const glm::dvec3& crosshair, int width, int height,
                          const glm::dmat3& rotation = glm::dmat3(1.0), double zoom = 1.0,
                          const glm::dvec2& pan = glm::dvec2(0.0));

// Samples (sampleImage) to 8-bit grey through the window (windowToGrey).
std::vector<std::uint8_t> windowedGrey(std::span<const float> samples, double center, double width);

// The crosshair moved into the box of the volume's voxel centres (in index
// space), where every plane through it shows voxels.
glm::dvec3 clampToVolume(const VolumeGeometry& geometry, const glm::dvec3& point);

} // namespace lucent
