#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/RenderDescription.h"
#include "core/scene/Renderer.h"
#include "core/volume/VolumePart.h"

namespace lucent {

struct CpuCasterCache; // core/raycast/CpuCasterCache.h

// The reference renderer: a CPU ray caster over one volume, multithreaded over
// image tiles. It keeps what depends only on the volume (B-spline
// coefficients, brick min/max) between renders, so a sequence of frames pays
// for them once. Double precision evaluates the transfer function exactly;
// float precision uses a 4096-entry table.
class CpuRayCaster : public Renderer {
public:
    explicit CpuRayCaster(const Volume& volume);
    // A caster of one part of a volume (a rank of a distributed render): it
    // draws only the part's owned box, on the whole volume's sample lattice and
    // view, premultiplied over transparent black, so that the parts' images
    // composited front to back give the whole volume's. `part` holds the
    // part's voxels with a halo (core/volume/VolumePart.h).
    CpuRayCaster(const Volume& part, const VolumePart& where);
    ~CpuRayCaster() override;
    CpuRayCaster(const CpuRayCaster&) = delete;
    CpuRayCaster& operator=(const CpuRayCaster&) = delete;

    // description.volume must be this caster's volume (or null). Throws
    // std::invalid_argument naming a setting that is out of range.
    RenderResult render(const RenderDescription& description) override;
    std::string backend() const override { return "cpu"; }
    std::string device() const override;
    // The last frame's split of its time: outside_cast_ms (validation, tables,
    // leap data, buffers: what a camera-only change costs beyond the rays) and
    // cast_ms (the rays); frame_buffers: recycled (a frame handed back lent
    // them) or new.
    FrameDetails frameDetails() const override;
    // The next frame of the spent one's size draws into its buffers instead of
    // allocating and clearing new ones (5 MB at 512 x 512, about 1 ms of a
    // drag's frame outside the cast).
    void recycle(RenderResult&& spent) override;

private:
    const Volume& volume_;
    std::optional<VolumePart> part_;
    std::unique_ptr<CpuCasterCache> cache_;
    double outsideCastMs_ = 0.0, castMs_ = 0.0;
    bool recycledBuffers_ = false;
};

} // namespace lucent
