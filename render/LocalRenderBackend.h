#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "render/GpuRayCaster.h"
#include "render/RenderBackend.h"

namespace lucent {

// The ray casters of this computer behind RenderBackend: GpuRayCaster in the
// caller's OpenGL context, or CpuRayCaster. They render in the caller's thread:
// request() only records the newest description and emits renderWanted(), and
// the caller (the 3D view's surface, from its paint with its context current)
// calls renderPending(), which emits frameReady() before it returns.
class LocalRenderBackend : public RenderBackend {
    Q_OBJECT

public:
    enum class Device { Gpu, Cpu };

    explicit LocalRenderBackend(QObject* parent = nullptr);
    // The GPU caster must have been released (releaseGl) with its context current.
    ~LocalRenderBackend() override;

    // Leaving Device::Gpu needs releaseGl() first (the caster's context current).
    void setDevice(Device device) { device_ = device; }
    Device device() const { return device_; }
    void setGpuOptions(const GpuOptions& options) { gpuOptions_ = options; }

    void setVolume(std::shared_ptr<const Volume> volume) override;
    void request(const RenderDescription& still, const FrameOptions& options) override;
    bool pending() const { return pending_.has_value(); }

    // Renders the newest request, if there is one. Device::Gpu needs a current
    // OpenGL 4.3 core context, the same one on every call until releaseGl().
    // A bad setting emits frameFailed(). When OpenGL fails (GlError, or
    // BudgetError: not even the coarsest level fits) the GPU caster is dropped,
    // gpuFailed() says why and the request stays pending for the next device.
    void renderPending();
    // Frees the GPU caster's textures and buffers: call with its context
    // current, before that context goes.
    void releaseGl();
    bool holdsGlResources() const { return gpuCaster_ != nullptr; }

    // The CPU caster of the current volume (made on first use).
    CpuRayCaster& cpuCaster();

signals:
    // A request is waiting: call renderPending() soon (from the paint).
    void renderWanted();
    void gpuFailed(const QString& reason);

private:
    struct Pending {
        RenderDescription still;
        FrameOptions options;
    };
    RenderResult renderOnGpu(const RenderDescription& description);

    Device device_ = Device::Cpu;
    GpuOptions gpuOptions_;
    std::shared_ptr<const Volume> volume_;
    std::uint64_t generation_ = 0;
    std::unique_ptr<GpuRayCaster> gpuCaster_;
    std::uint64_t gpuGeneration_ = 0;
    std::unique_ptr<CpuRayCaster> cpuCaster_;
    std::optional<Pending> pending_;
};

} // namespace lucent
