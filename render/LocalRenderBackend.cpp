#include "render/LocalRenderBackend.h"

#include <chrono>
#include <stdexcept>

#include "core/volume/BrickResidency.h"
#include "render/GlError.h"

namespace lucent {

LocalRenderBackend::LocalRenderBackend(QObject* parent) : RenderBackend(parent) {}

LocalRenderBackend::~LocalRenderBackend() = default;

void LocalRenderBackend::setVolume(std::shared_ptr<const Volume> volume) {
    // The GPU caster is remade on the next render, in its context.
    cpuCaster_.reset();
    volume_ = std::move(volume);
    ++generation_;
    pending_.reset();
}

void LocalRenderBackend::request(const RenderDescription& still, const FrameOptions& options) {
    pending_ = Pending{still, options};
    emit renderWanted();
}

CpuRayCaster& LocalRenderBackend::cpuCaster() {
    if (!volume_) {
        throw std::logic_error("LocalRenderBackend: no volume");
    }
    if (!cpuCaster_) {
        cpuCaster_ = std::make_unique<CpuRayCaster>(*volume_);
    }
    return *cpuCaster_;
}

void LocalRenderBackend::releaseGl() {
    gpuCaster_.reset();
}

RenderResult LocalRenderBackend::renderOnGpu(const RenderDescription& description) {
    if (!gpuCaster_ || gpuGeneration_ != generation_) {
        gpuCaster_.reset();
        gpuCaster_ = std::make_unique<GpuRayCaster>(*volume_, gpuOptions_);
        gpuGeneration_ = generation_;
    }
    return gpuCaster_->render(description);
}

void LocalRenderBackend::renderPending() {
    if (!pending_) {
        return;
    }
    if (!volume_ || volume_->empty()) {
        pending_.reset();
        return;
    }
    const Pending job = *pending_;
    BackendFrame frame;
    frame.interactive = job.options.interactive;
    try {
        RenderDescription d = job.options.interactive
                                  ? interactiveDescription(job.still, job.options.quality)
                                  : job.still;
        d.volume = volume_.get();
        const auto start = std::chrono::steady_clock::now();
        RenderResult result = device_ == Device::Gpu ? renderOnGpu(d) : cpuCaster().render(d);
        frame.renderMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        frame.image = std::move(result.image);
        frame.stats = result.stats;
    } catch (const GlError& e) {
        gpuCaster_.reset();
        emit gpuFailed(QString::fromStdString(e.what()));
        return;
    } catch (const BudgetError& e) {
        gpuCaster_.reset();
        emit gpuFailed(QString::fromStdString(e.what()));
        return;
    } catch (const std::exception& e) {
        pending_.reset();
        emit frameFailed(QString::fromStdString(e.what()));
        return;
    }
    pending_.reset();
    emit frameReady(frame);
}

} // namespace lucent
