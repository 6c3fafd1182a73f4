#include "render/RenderDevice.h"

#include <stdexcept>

#include "core/raycast/CpuRayCaster.h"
#include "render/GlError.h"
#include "render/OffscreenContext.h"

namespace lucent {
namespace {

// A GPU ray caster in a context of its own: current whenever it works, and
// when the caster frees its textures.
class OwnContextRenderer final : public Renderer {
public:
    OwnContextRenderer(std::shared_ptr<OffscreenContext> context,
                       std::unique_ptr<GpuRayCaster> caster)
        : context_(std::move(context)), caster_(std::move(caster)) {}
    ~OwnContextRenderer() override {
        context_->makeCurrent();
        caster_.reset();
    }
    RenderResult render(const RenderDescription& description) override {
        context_->makeCurrent();
        return caster_->render(description);
    }
    std::string backend() const override { return caster_->backend(); }
    std::string device() const override { return context_->description(); }
    FrameDetails frameDetails() const override { return caster_->frameDetails(); }
    // Into a framebuffer of this renderer's own context.
    bool drawsInPlace() const override { return caster_->drawsInPlace(); }
    RenderStats drawInPlace(const RenderDescription& description,
                            const FramebufferTarget& target) override {
        context_->makeCurrent();
        return caster_->drawInPlace(description, target);
    }
    bool setSurface(std::shared_ptr<const SurfaceDisplay> surface) override {
        return caster_->setSurface(std::move(surface)); // GL-free: uploaded with the next frame
    }

private:
    std::shared_ptr<OffscreenContext> context_;
    std::unique_ptr<GpuRayCaster> caster_;
};

} // namespace

RendererKind parseRendererKind(std::string_view name) {
    if (name == "cpu") {
        return RendererKind::Cpu;
    }
    if (name == "gl") {
        return RendererKind::Gl;
    }
    throw std::invalid_argument("backend '" + std::string(name) + "' is not one of cpu, gl");
}

const char* rendererKindName(RendererKind kind) {
    return kind == RendererKind::Gl ? "gl" : "cpu";
}

RenderDevice::RenderDevice(RendererKind kind, std::shared_ptr<OffscreenContext> context,
                           std::string fallbackReason)
    : kind_(kind), context_(std::move(context)), fallbackReason_(std::move(fallbackReason)) {}

RenderDevice::~RenderDevice() = default;

std::unique_ptr<RenderDevice> RenderDevice::open(RendererKind wanted, int eglDevice) {
    if (wanted == RendererKind::Cpu) {
        return std::unique_ptr<RenderDevice>(new RenderDevice(RendererKind::Cpu, nullptr, {}));
    }
    try {
        std::shared_ptr<OffscreenContext> context = OffscreenContext::create(eglDevice);
        return std::unique_ptr<RenderDevice>(
            new RenderDevice(RendererKind::Gl, std::move(context), {}));
    } catch (const GlError& e) {
        return std::unique_ptr<RenderDevice>(
            new RenderDevice(RendererKind::Cpu, nullptr,
                             std::string("the GL backend is not available (") + e.what() + ")"));
    }
}

std::unique_ptr<RenderDevice> RenderDevice::borrowCurrentContext() {
    return std::unique_ptr<RenderDevice>(new RenderDevice(RendererKind::Gl, nullptr, {}));
}

std::string RenderDevice::description() const {
    if (kind_ == RendererKind::Cpu) {
        return "cpu";
    }
    return context_ ? "gl: " + context_->description() : "gl";
}

RenderDevice::Opened RenderDevice::openRenderer(const Volume& volume,
                                                const GpuOptions& options) const {
    return openWith([&] { return std::make_unique<GpuRayCaster>(volume, options); },
                    [&] { return std::make_unique<CpuRayCaster>(volume); });
}

RenderDevice::Opened RenderDevice::openPartRenderer(const Volume& part, const VolumePart& where,
                                                    const GpuOptions& options) const {
    return openWith([&] { return std::make_unique<GpuRayCaster>(part, where, options); },
                    [&] { return std::make_unique<CpuRayCaster>(part, where); });
}

RenderDevice::Opened
RenderDevice::openWith(const std::function<std::unique_ptr<GpuRayCaster>()>& gpu,
                       const std::function<std::unique_ptr<Renderer>()>& cpu) const {
    Opened opened;
    if (kind_ == RendererKind::Gl) {
        try {
            if (context_) {
                context_->makeCurrent();
                opened.renderer = std::make_unique<OwnContextRenderer>(context_, gpu());
            } else {
                opened.renderer = gpu();
            }
            return opened;
        } catch (const GlError& e) {
            opened.fallbackReason =
                std::string("the GPU ray caster is not available (") + e.what() + ")";
        }
    }
    opened.renderer = cpu();
    return opened;
}

} // namespace lucent
