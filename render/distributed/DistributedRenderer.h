#pragma once
// One volume rendered by all the ranks of an MPI job (docs/distributed.md):
// each rank ray-casts its part (PartLoader.h) on the whole volume's sample
// lattice, and IceT composites the parts in visibility order. A Renderer like
// the others; render() is collective: every rank calls it with the same
// description, and rank 0 receives the image (the others an empty one).

#include <memory>
#include <string>
#include <vector>

#include "core/scene/Renderer.h"
#include "render/distributed/Communicator.h"
#include "render/distributed/PartLoader.h"

namespace lucent {

class IceTCompositor;

class DistributedRenderer : public Renderer {
public:
    // `comm` must outlive the renderer. Collective.
    DistributedRenderer(const Communicator& comm, LoadedPart part);
    ~DistributedRenderer() override;
    DistributedRenderer(const DistributedRenderer&) = delete;
    DistributedRenderer& operator=(const DistributedRenderer&) = delete;

    // Collective. The description's volume is ignored (each rank renders its
    // part). Throws DistributedError on every rank when a rank fails, naming
    // it; std::invalid_argument for a description out of range (on every
    // rank alike).
    RenderResult render(const RenderDescription& description) override;
    // The ranks' backend: "cpu".
    std::string backend() const override { return "cpu"; }
    std::string device() const override;
    // ranks, composite_ms, render_ms_max, render_ms_min, rank_voxels_max,
    // rank_resident_mib_max, icet_bytes_sent_max and the strategy.
    FrameDetails frameDetails() const override { return details_; }

    const LoadedPart& part() const { return part_; }

private:
    std::vector<glm::vec4> compositeParts(const RenderDescription& d, const RenderResult& mine,
                                          const std::vector<int>& order);

    const Communicator& comm_;
    LoadedPart part_;
    std::unique_ptr<Renderer> caster_;
    std::unique_ptr<IceTCompositor> icet_;
    FrameDetails details_;
    double averageMs_ = 0.0;
};

} // namespace lucent
