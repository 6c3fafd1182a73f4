#include "app/bench/BenchFrames.h"

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "app/bench/BenchScenes.h"

namespace lucent::bench {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

constexpr int kDragFrames = 12;

double detailMs(const FrameDetails& details, const std::string& key) {
    const std::optional<std::string> value = frameDetail(details, key);
    return value ? std::stod(*value) : 0.0;
}

} // namespace

TurnFrames turnFrames(const FrameFunction& render, const RenderDescription& d, int turns) {
    TurnFrames out;
    std::vector<double> ms;
    for (int frame = 0; frame <= turns; ++frame) {
        RenderDescription f = d;
        f.camera.azimuth = d.camera.azimuth + 5.0 * std::max(0, frame - 1);
        const auto t0 = Clock::now();
        GpuRenderResult r = render(f);
        (frame == 0 ? out.firstMs : ms.emplace_back()) = msSince(t0);
        out.uploadedMib += double(r.gpu.bytesUploaded) / 1048576.0;
        if (frame == 1) {
            out.first = std::move(r);
        }
    }
    out.medianMs = median(ms);
    return out;
}

TurnFrames turnFrames(GpuRayCaster& gpu, const RenderDescription& d, int turns) {
    return turnFrames([&](const RenderDescription& f) { return gpu.renderWithGpuStats(f); }, d,
                      turns);
}

TurnFrames turnFrames(CpuRayCaster& cpu, const RenderDescription& d, int turns) {
    return turnFrames(
        [&](const RenderDescription& f) {
            return GpuRenderResult{cpu.render(f), {}};
        },
        d, turns);
}

DragOverhead dragOverhead(GpuRayCaster& gpu, RenderDescription d,
                          const TransferFunction* alternate) {
    if (alternate != nullptr) { // both resident before timing
        RenderDescription other = d;
        other.transferFunction = *alternate;
        gpu.renderWithGpuStats(other);
    }
    gpu.renderWithGpuStats(d);
    const TransferFunction base = d.transferFunction;
    std::vector<double> prepare, cast;
    DragOverhead o;
    for (int frame = 1; frame <= kDragFrames; ++frame) {
        d.camera.azimuth = 3.0 * frame;
        if (alternate != nullptr) {
            d.transferFunction = frame % 2 ? *alternate : base;
        }
        const GpuRenderResult r = gpu.renderWithGpuStats(d);
        prepare.push_back(r.gpu.prepareMs);
        cast.push_back(r.gpu.castMs);
        o.planned += r.gpu.bricksPlanned ? 1 : 0;
    }
    o.outsideCastMs = median(prepare);
    o.castMs = median(cast);
    return o;
}

DragOverhead dragOverhead(CpuRayCaster& cpu, RenderDescription d) {
    cpu.recycle(cpu.render(d));
    std::vector<double> outside, cast;
    for (int frame = 1; frame <= kDragFrames; ++frame) {
        d.camera.azimuth = 3.0 * frame;
        cpu.recycle(cpu.render(d)); // as a view that has shown its frame hands it back
        const FrameDetails details = cpu.frameDetails();
        outside.push_back(detailMs(details, "outside_cast_ms"));
        cast.push_back(detailMs(details, "cast_ms"));
    }
    return {median(outside), median(cast), 0};
}

} // namespace lucent::bench
