#include "render/LocalRenderBackend.h"

#include <chrono>
#include <stdexcept>

#include "core/volume/BrickResidency.h"
#include "render/GlError.h"
#include "render/SurfaceRenderer.h"

namespace lucent {

LocalRenderBackend::LocalRenderBackend(QObject* parent) : RenderBackend(parent) {}

LocalRenderBackend::~LocalRenderBackend() = default;

void LocalRenderBackend::setKind(RendererKind kind) {
    if (kind == kind_) {
        return;
    }
    if (holdsGlResources()) {
        throw std::logic_error("LocalRenderBackend: the GL renderer must be released (releaseGl, "
                               "its context current) before another kind renders");
    }
    dropRenderer();
    kind_ = kind;
}

void LocalRenderBackend::setVolume(std::shared_ptr<const Volume> volume) {
    // A GL renderer is remade on the next render, in its context; it keeps
    // the volume it renders alive until then.
    if (!holdsGlResources()) {
        dropRenderer();
    }
    volume_ = std::move(volume);
    pending_.reset();
}

void LocalRenderBackend::setSurface(std::shared_ptr<const SurfaceDisplay> surface) {
    if (surface) {
        checkSurfaceDisplay(*surface);
    }
    surface_ = std::move(surface);
    if (renderer_) {
        rendererDrawsSurfaces_ = renderer_->setSurface(surface_);
        if (lastInPlace_) {
            emit renderWanted(); // drawPending() draws the last frame again, with it
        }
    }
}

bool LocalRenderBackend::surfaceShown() const {
    return surface_ != nullptr && (renderer_ ? rendererDrawsSurfaces_ : kind_ == RendererKind::Gl);
}

void LocalRenderBackend::request(const RenderDescription& still, const FrameOptions& options) {
    pending_ = Pending{still, options};
    emit renderWanted();
}

void LocalRenderBackend::dropRenderer() {
    renderer_.reset();
    rendererVolume_.reset();
    rendererIsGl_ = false;
    rendererDrawsSurfaces_ = false;
    last_.reset();
    lastInPlace_ = false;
}

void LocalRenderBackend::releaseGl() {
    if (rendererIsGl_) {
        dropRenderer();
    }
}

Renderer& LocalRenderBackend::renderer() {
    if (renderer_ && rendererVolume_ != volume_) {
        dropRenderer(); // a GL one with its context current: we are rendering
    }
    if (!renderer_) {
        const std::unique_ptr<RenderDevice> device = kind_ == RendererKind::Gl
                                                         ? RenderDevice::borrowCurrentContext()
                                                         : RenderDevice::open(RendererKind::Cpu);
        RenderDevice::Opened opened = device->openRenderer(*volume_, gpuOptions_);
        if (!opened.fallbackReason.empty()) {
            // The CPU renderer it opened instead belongs on the CPU surface.
            throw GlError(opened.fallbackReason);
        }
        renderer_ = std::move(opened.renderer);
        rendererDrawsSurfaces_ = renderer_->setSurface(surface_);
        rendererVolume_ = volume_;
        rendererIsGl_ = kind_ == RendererKind::Gl;
    }
    return *renderer_;
}

bool LocalRenderBackend::renderJob(const FramebufferTarget* target) {
    const Pending job = *pending_;
    BackendFrame frame;
    RenderResult spent; // handed back to the renderer once the frame is shown
    frame.interactive = job.options.interactive;
    try {
        RenderDescription d = job.options.interactive
                                  ? interactiveDescription(job.still, job.options.quality)
                                  : job.still;
        d.volume = volume_.get();
        Renderer& r = renderer();
        const bool inPlace = target != nullptr && r.drawsInPlace();
        const auto start = std::chrono::steady_clock::now();
        if (inPlace) {
            frame.stats = r.drawInPlace(d, *target);
            frame.inPlace = true;
        } else {
            spent = r.render(d);
            frame.image = std::move(spent.image);
            frame.stats = spent.stats;
        }
        frame.renderMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        if (target != nullptr && !inPlace) {
            clearFramebuffer(*target, glm::dvec3(0.0)); // the surface paints the image
        }
        last_ = d;
        lastInPlace_ = inPlace;
    } catch (const GlError& e) {
        dropRenderer();
        emit gpuFailed(QString::fromStdString(e.what()));
        return false;
    } catch (const BudgetError& e) {
        dropRenderer();
        emit gpuFailed(QString::fromStdString(e.what()));
        return false;
    } catch (const std::exception& e) {
        pending_.reset();
        emit frameFailed(QString::fromStdString(e.what()));
        return false;
    }
    pending_.reset();
    emit frameReady(frame);
    // The receivers have copied what they keep: the next frame of this size
    // draws into these buffers (a drag allocates and clears nothing).
    if (renderer_ != nullptr && !frame.inPlace) {
        spent.image = std::move(frame.image);
        renderer_->recycle(std::move(spent));
    }
    if (frame.stats.bricksPending > 0 && !pending_) {
        // Bricks still stream in: the same frame again, finer, unless a newer one is asked for.
        pending_ = job;
        emit renderWanted();
    }
    return true;
}

void LocalRenderBackend::renderPending() {
    if (!pending_) {
        return;
    }
    if (!volume_ || volume_->empty()) {
        pending_.reset();
        return;
    }
    renderJob(nullptr);
}

bool LocalRenderBackend::drawLast(const FramebufferTarget& target) {
    if (!renderer_ || rendererVolume_ != volume_ || !last_ || !lastInPlace_) {
        return false;
    }
    try {
        renderer_->drawInPlace(*last_, target);
        return true;
    } catch (const GlError& e) {
        dropRenderer();
        emit gpuFailed(QString::fromStdString(e.what()));
    } catch (const BudgetError& e) {
        dropRenderer();
        emit gpuFailed(QString::fromStdString(e.what()));
    } catch (const std::exception& e) {
        last_.reset();
        emit frameFailed(QString::fromStdString(e.what()));
    }
    return false;
}

void LocalRenderBackend::drawPending(const FramebufferTarget& target) {
    if (pending_ && (!volume_ || volume_->empty())) {
        pending_.reset();
    }
    if (pending_ && renderJob(&target)) {
        return;
    }
    // No new frame (or it failed): the last one again, else black.
    if (drawLast(target)) {
        return;
    }
    try {
        clearFramebuffer(target, glm::dvec3(0.0));
    } catch (const GlError& e) {
        dropRenderer();
        emit gpuFailed(QString::fromStdString(e.what()));
    }
}

FrameDetails LocalRenderBackend::lastFrameDetails() const {
    return renderer_ != nullptr ? renderer_->frameDetails() : FrameDetails{};
}

ImageRGBA8 LocalRenderBackend::readLastFrame() {
    if (!renderer_ || rendererVolume_ != volume_ || !last_) {
        return {};
    }
    return renderer_->render(*last_).image;
}

} // namespace lucent
