#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/scene/RenderDescription.h"
#include "core/scene/Renderer.h"

namespace lucent {

// The reference renderer: a CPU ray caster over one volume, multithreaded over
// image tiles. It keeps what depends only on the volume (B-spline
// coefficients, brick min/max) between renders, so a sequence of frames pays
// for them once. Double precision evaluates the transfer function exactly;
// float precision uses a 4096-entry table.
class CpuRayCaster : public Renderer {
public:
    explicit CpuRayCaster(const Volume& volume);
    ~CpuRayCaster() override;
    CpuRayCaster(const CpuRayCaster&) = delete;
    CpuRayCaster& operator=(const CpuRayCaster&) = delete;

    // description.volume must be this caster's volume (or null). Throws
    // std::invalid_argument naming a setting that is out of range.
    RenderResult render(const RenderDescription& description) override;
    std::string backend() const override { return "cpu"; }
    std::string device() const override;

private:
    struct Cache;
    const Volume& volume_;
    std::unique_ptr<Cache> cache_;
};

} // namespace lucent
