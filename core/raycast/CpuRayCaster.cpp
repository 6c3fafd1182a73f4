#include "core/raycast/CpuRayCaster.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string_view>
#include <thread>
#include <type_traits>

#include "core/raycast/BrickVisibility.h"
#include "core/raycast/CastImage.h"
#include "core/raycast/CpuCasterCache.h"
#include "core/raycast/FastDvrKernel.h"
#include "core/raycast/OverlaySampler.h"
#include "core/raycast/PacketDvrKernel.h"
#include "core/raycast/RayKernel.h"
#include "core/scene/ViewFrame.h"

namespace lucent {

namespace {

static_assert(kPacket == PacketDvrKernel<std::int16_t>::kWidth);

// SIMD packets where the CPU has them, unless LUCENT_NO_SIMD=1 (read once)
// asks for the scalar kernels, e.g. to compare timings from the command line.
bool simdAllowed() {
    static const bool allowed = [] {
        const char* v = std::getenv("LUCENT_NO_SIMD");
        return packetKernelSupported() && !(v != nullptr && std::string_view(v) == "1");
    }();
    return allowed;
}

// Times a frame: the rays (added by the caller around the cast) and, when the
// frame ends by any path, the rest.
class FrameClock {
public:
    using Clock = std::chrono::steady_clock;
    FrameClock(double& outsideMs, double& castMs) : outside_(outsideMs), cast_(castMs) {
        cast_ = 0.0;
    }
    ~FrameClock() { outside_ = millisecondsSince(start_) - cast_; }
    FrameClock(const FrameClock&) = delete;
    FrameClock& operator=(const FrameClock&) = delete;
    template <class F> void timeCast(F&& f) {
        const auto t0 = Clock::now();
        f();
        cast_ += millisecondsSince(t0);
    }

private:
    static double millisecondsSince(Clock::time_point t) {
        return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
    }
    Clock::time_point start_ = Clock::now();
    double& outside_;
    double& cast_;
};

// Where a frame's rays go: its view, the description as the rays see it (a
// part's clip box and background), the result, and the clock that times the cast.
struct FrameTarget {
    ViewFrame view;
    const RenderDescription& local;
    RenderResult& result;
    std::vector<glm::vec2>* projection;
    FrameClock& clock;
};

// The kernel for the description's sampling and precision and for this CPU:
// the SIMD packets, the scalar fast kernel, or the generic one (also the one
// that draws an overlay along the rays).
class KernelChoice {
public:
    KernelChoice(const Volume& volume, const RenderDescription& desc, const float* coefficientsF,
                 const double* coefficientsD)
        : volume_(volume), desc_(desc), coefficientsF_(coefficientsF),
          coefficientsD_(coefficientsD) {}

    template <class Real> void cast(const RaySetup<Real>& setup, const FrameTarget& t) const {
        const glm::ivec3 dims = volume_.dims();
        const SamplingSettings& sampling = desc_.sampling;
        if (sampling.interpolation == Interpolation::Cubic) {
            const Real* c = nullptr;
            if constexpr (std::is_same_v<Real, double>) {
                c = coefficientsD_;
            } else {
                c = coefficientsF_;
            }
            castWith(setup, CubicField<Real>{Grid<Real, Real>(c, dims)}, t);
            return;
        }
        const bool alone = desc_.overlay.volume == nullptr;
        visitVoxels(volume_, [&](auto v) {
            using T = std::remove_const_t<typename decltype(v)::element_type>;
            const Grid<Real, T> grid(v.data(), dims);
            if (sampling.interpolation == Interpolation::Nearest) {
                castWith(setup, NearestField<Real, T>{grid}, t);
                return;
            }
            if constexpr (std::is_same_v<Real, float>) {
                if (alone && sampling.simd && simdAllowed() &&
                    PacketDvrKernel<T>::applies(setup, dims)) {
                    castImageWith(PacketDvrKernel<T>(setup, grid), t);
                    return;
                }
                if (alone && FastDvrKernel<T>::applies(setup, dims)) {
                    castImageWith(FastDvrKernel<T>(setup, grid), t);
                    return;
                }
            }
            castWith(setup, LinearField<Real, T>{grid}, t);
        });
    }

private:
    template <class Kernel> void castImageWith(const Kernel& kernel, const FrameTarget& t) const {
        t.clock.timeCast([&] {
            castImage(kernel, volume_.geometry(), t.view, t.local, t.result.image,
                      t.result.premultiplied, t.result.stats.samples, t.projection);
        });
    }

    // The generic kernel, with the overlay along the same rays where there is one.
    template <class Real, class Field>
    void castWith(const RaySetup<Real>& setup, const Field& field, const FrameTarget& t) const {
        const Volume* overlay = desc_.overlay.volume;
        if (overlay == nullptr) {
            castImageWith(RayKernel<Real, Field>(setup, field), t);
            return;
        }
        const FusionStyle& style = desc_.overlay.style;
        const OverlayTable entries = overlayTable(style, desc_.sampling.step);
        OverlaySampler<Real> sampler{LinearField<Real, float>{Grid<Real, float>(
                                         overlay->voxels<float>().data(), volume_.dims())},
                                     &entries, 0.0, 1.0};
        sampler.low = style.center - 0.5 * style.width;
        sampler.width = std::max(style.width, 1e-9);
        castImageWith(RayKernel<Real, Field, OverlaySampler<Real>>(setup, field, sampler), t);
    }

    const Volume& volume_;
    const RenderDescription& desc_;
    const float* coefficientsF_;
    const double* coefficientsD_;
};

} // namespace

CpuRayCaster::CpuRayCaster(const Volume& volume)
    : volume_(volume), cache_(std::make_unique<CpuCasterCache>()) {
    cache_->range = volume.valueRange();
}

CpuRayCaster::CpuRayCaster(const Volume& part, const VolumePart& where)
    : volume_(part), part_(where), cache_(std::make_unique<CpuCasterCache>()) {
    cache_->range = where.valueRange;
}

CpuRayCaster::~CpuRayCaster() = default;

void CpuRayCaster::recycle(RenderResult&& spent) {
    const std::size_t n = std::size_t(spent.image.width) * std::size_t(spent.image.height);
    if (spent.image.pixels.size() != 4 * n || spent.premultiplied.size() != n) {
        return; // not a whole frame of this caster's: the spare buffers stay
    }
    cache_->spareImage = std::move(spent.image);
    cache_->sparePremultiplied = std::move(spent.premultiplied);
}

std::string CpuRayCaster::device() const {
    return "cpu: " + std::to_string(std::max(1u, std::thread::hardware_concurrency())) + " threads";
}

FrameDetails CpuRayCaster::frameDetails() const {
    const auto fixed = [](double v) {
        char text[32];
        std::snprintf(text, sizeof text, "%.3f", v);
        return std::string(text);
    };
    return {{"outside_cast_ms", fixed(outsideCastMs_)},
            {"cast_ms", fixed(castMs_)},
            {"frame_buffers", recycledBuffers_ ? "recycled" : "new"}};
}

RenderResult CpuRayCaster::render(const RenderDescription& desc) {
    FrameClock clock(outsideCastMs_, castMs_);
    desc.validate();
    if (desc.volume != nullptr && desc.volume != &volume_) {
        throw std::invalid_argument("render description names another volume than this caster's");
    }
    const Volume* overlay = desc.overlay.volume;
    if (overlay != nullptr && overlay->dims() != volume_.dims()) {
        throw std::invalid_argument("the overlay's grid is not this caster's volume's");
    }
    if (overlay != nullptr && part_) {
        throw std::invalid_argument("a part of a distributed render draws no overlay");
    }
    CpuFrameSetup setup;
    cache_->prepare(volume_, part_, desc, setup);

    RenderResult result;
    recycledBuffers_ = cache_->takeFrameBuffers(desc.width, desc.height, result);
    // A part draws its box in its own indices, over transparent black, seen as
    // the whole volume is.
    RenderDescription local = desc;
    if (part_) {
        local.clip = ClipBox{setup.sf.clipLo, setup.sf.clipHi};
        local.background = glm::dvec3(0.0);
    }
    result.stats.bricksTotal = setup.grid->count();
    result.stats.bricksUsed = visibleBricks(*setup.grid, setup.visible, local.clip).size();
    // A part's projections are composited from their values (and counts).
    const bool projecting =
        part_ && (desc.mode == RenderMode::Mip || desc.mode == RenderMode::MinIp ||
                  desc.mode == RenderMode::Average);
    if (projecting) {
        result.projection.assign(result.premultiplied.size(), glm::vec2(0.0f));
    }
    // A part whose box the clip box leaves out draws nothing.
    if (part_ && glm::any(glm::lessThan(setup.sf.clipHi, setup.sf.clipLo))) {
        result.stats.bricksUsed = 0;
        std::fill(result.image.pixels.begin(), result.image.pixels.end(), std::uint8_t(0));
        std::fill(result.premultiplied.begin(), result.premultiplied.end(), glm::vec4(0.0f));
        return result;
    }
    const FrameTarget target{makeViewFrame(part_ ? part_->whole : volume_.geometry(), desc.camera,
                                           desc.width, desc.height),
                             local, result, projecting ? &result.projection : nullptr, clock};
    const KernelChoice choice{volume_, desc, cache_->coefficientsF.data(),
                              cache_->coefficientsD.data()};
    if (setup.exact) {
        choice.cast(setup.sd, target);
    } else {
        choice.cast(setup.sf, target);
    }
    return result;
}

} // namespace lucent
