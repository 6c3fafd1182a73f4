#pragma once

#include <memory>
#include <vector>

#include "core/image/Image.h"
#include "core/scene/RenderDescription.h"

namespace lucent {

struct RenderStats {
    std::size_t samples = 0;     // volume samples taken along all rays
    std::size_t bricksTotal = 0; // bricks of the volume
    std::size_t bricksUsed = 0;  // bricks visible under the transfer function and clip box
    int lod = 0;                 // level of detail rendered (0: full resolution)
};

struct RenderResult {
    ImageRGBA8 image;                     // opaque: composited over the background
    std::vector<glm::vec4> premultiplied; // per pixel, before the background (row-major)
    RenderStats stats;
};

// The reference renderer: a CPU ray caster over one volume, multithreaded over
// image tiles. It keeps what depends only on the volume (B-spline
// coefficients, brick min/max) between renders, so a sequence of frames pays
// for them once. Double precision evaluates the transfer function exactly;
// float precision uses a 4096-entry table.
class CpuRayCaster {
public:
    explicit CpuRayCaster(const Volume& volume);
    ~CpuRayCaster();
    CpuRayCaster(const CpuRayCaster&) = delete;
    CpuRayCaster& operator=(const CpuRayCaster&) = delete;

    // description.volume must be this caster's volume (or null). Throws
    // std::invalid_argument naming a setting that is out of range.
    RenderResult render(const RenderDescription& description);

private:
    struct Cache;
    const Volume& volume_;
    std::unique_ptr<Cache> cache_;
};

} // namespace lucent
