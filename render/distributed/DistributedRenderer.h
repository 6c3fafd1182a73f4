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
#include "render/RenderDevice.h"
#include "render/distributed/Communicator.h"
#include "render/distributed/PartLoader.h"

namespace lucent {

class IceTCompositor;

class DistributedRenderer : public Renderer {
public:
    // `comm` must outlive the renderer. Collective. Each rank renders on the
    // CPU, or with GL where `kind` asks for it and the rank can make a
    // context (else on its CPU, and frameDetails() says so).
    DistributedRenderer(const Communicator& comm, LoadedPart part,
                        RendererKind kind = RendererKind::Cpu);
    ~DistributedRenderer() override;
    DistributedRenderer(const DistributedRenderer&) = delete;
    DistributedRenderer& operator=(const DistributedRenderer&) = delete;

    // Collective. The description's volume is ignored (each rank renders its
    // part). Throws DistributedError on every rank when a rank fails, naming
    // it; std::invalid_argument for a description out of range (on every
    // rank alike).
    RenderResult render(const RenderDescription& description) override;
    // The ranks' backend: "gl" where every rank renders with GL, else "cpu".
    std::string backend() const override { return backend_; }
    std::string device() const override;
    // ranks, composite_ms, render_ms_max, render_ms_min, rank_voxels_max,
    // rank_resident_mib_max, icet_bytes_sent_max and the strategy.
    FrameDetails frameDetails() const override { return details_; }

    const LoadedPart& part() const { return part_; }

private:
    FrameDetails partFigures() const; // collective
    std::vector<glm::vec4> compositeParts(const RenderDescription& d, const RenderResult& mine,
                                          const std::vector<int>& order);

    const Communicator& comm_;
    LoadedPart part_;
    std::unique_ptr<RenderDevice> device_;
    std::unique_ptr<Renderer> caster_;
    std::string backend_ = "cpu";
    std::string fallback_; // why this rank renders on the CPU where GL was asked
    std::unique_ptr<IceTCompositor> icet_;
    FrameDetails details_;
    FrameDetails partFigures_; // gathered once, at construction
    double averageMs_ = 0.0;
};

} // namespace lucent
