#include "core/raycast/CpuRayCaster.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <thread>
#include <tuple>

#include "core/raycast/BSplinePrefilter.h"
#include "core/raycast/BrickVisibility.h"
#include "core/raycast/CastImage.h"
#include "core/raycast/FastDvrKernel.h"
#include "core/raycast/InvisibleCells.h"
#include "core/raycast/LeapReach.h"
#include "core/raycast/OverlayLeaping.h"
#include "core/raycast/OverlaySampler.h"
#include "core/raycast/PacketDvrKernel.h"
#include "core/raycast/RayKernel.h"
#include "core/scene/ViewFrame.h"

namespace lucent {

struct CpuRayCaster::Cache {
    std::pair<double, double> range{0.0, 0.0};
    std::vector<float> coefficientsF;
    std::vector<double> coefficientsD;
    std::pair<double, double> coefficientRange{0.0, 0.0};
    std::map<std::tuple<int, bool, int>, BrickGrid> grids; // (size, over coefficients, overlap)
    // What the last render derived from the transfer function, the sampling
    // and the leaping levels (tables, leap decisions, leap reach): frames that
    // only move the camera reuse it. Valid while `key` equals the render's.
    struct ClassificationKey {
        TransferFunction tf;
        RenderMode mode = RenderMode::Dvr;
        double isoValue = 0.0, tLo = 0.0, tHi = 0.0, step = 0.0;
        bool exact = false, preintegrate = false, cubic = false;
        int brickSize = 0, cellSize = 0, cellOverlap = 0;
        bool operator==(const ClassificationKey&) const = default;
    };
    struct LevelData {
        std::vector<std::uint8_t> skippable;
        std::vector<glm::vec2> range;
    };
    std::optional<ClassificationKey> key;
    std::vector<glm::vec4> rawTable, table;
    PreintegrationTable preTable; // float pre-integration (3-22 ms to build)
    LevelData coarse, fine;
    std::vector<std::uint8_t> cellLeap, reach;
    std::vector<std::int32_t> leapReach; // cellLeap | reach << 8
    // Cells no sample can see (fast kernels), and the bounds they were found for.
    std::optional<std::pair<double, double>> invisibleBounds;
    InvisibleCells invisible;
    OverlayLeaping overlayLeaping; // a fused DVR render's leaping decisions
    // A frame handed back (recycle): its buffers, for the next frame of its size.
    ImageRGBA8 spareImage;
    std::vector<glm::vec4> sparePremultiplied;

    // The frame's image and premultiplied colours: the spare ones when their
    // size matches, else new ones. castImage writes every pixel of both
    // (premultiplied 0 where no ray is cast), so spare ones are not cleared.
    // Returns whether they were spare ones.
    bool takeFrameBuffers(int width, int height, RenderResult& r) {
        const std::size_t n = std::size_t(width) * std::size_t(height);
        if (spareImage.width == width && spareImage.height == height &&
            spareImage.pixels.size() == 4 * n && sparePremultiplied.size() == n) {
            r.image = std::move(spareImage);
            r.premultiplied = std::move(sparePremultiplied);
            spareImage = ImageRGBA8{};
            sparePremultiplied = {};
            return true;
        }
        r.image = ImageRGBA8::filled(width, height, 0);
        r.premultiplied.assign(n, glm::vec4(0.0f));
        spareImage = ImageRGBA8{};
        sparePremultiplied = {};
        return false;
    }
};

namespace {

constexpr int kTableSize = 4096;
constexpr int kPreintegrationSize = 256;
static_assert(kPacket == PacketDvrKernel<std::int16_t>::kWidth);
constexpr int kLeapCell = 8;

// SIMD packets where the CPU has them, unless LUCENT_NO_SIMD=1 (read once)
// asks for the scalar kernels, e.g. to compare timings from the command line.
bool simdAllowed() {
    static const bool allowed = [] {
        const char* v = std::getenv("LUCENT_NO_SIMD");
        return packetKernelSupported() && !(v != nullptr && std::string_view(v) == "1");
    }();
    return allowed;
}

// Per fine cell: 2 where the brick holding the whole cell can be leapt, 1 where
// the cell can, 0 where neither.
std::vector<std::uint8_t> leapCodes(const BrickGrid& bricks,
                                    const std::vector<std::uint8_t>& brickSkip,
                                    const BrickGrid& cells,
                                    const std::vector<std::uint8_t>& cellSkip) {
    std::vector<std::uint8_t> codes(cells.count(), 0);
    const int b = bricks.brickSize();
#pragma omp parallel for schedule(static)
    for (std::size_t n = 0; n < cells.count(); ++n) {
        const Brick& c = cells.bricks()[n];
        const glm::ivec3 lo = c.first / b, hi = (c.last - 1) / b;
        if (lo == hi && brickSkip[bricks.idOf(lo)] != 0) {
            codes[n] = 2;
        } else {
            codes[n] = cellSkip[n];
        }
    }
    return codes;
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

} // namespace

CpuRayCaster::CpuRayCaster(const Volume& volume)
    : volume_(volume), cache_(std::make_unique<Cache>()) {
    cache_->range = volume.valueRange();
}

CpuRayCaster::CpuRayCaster(const Volume& part, const VolumePart& where)
    : volume_(part), part_(where), cache_(std::make_unique<Cache>()) {
    cache_->range = where.valueRange;
}

CpuRayCaster::~CpuRayCaster() = default;

void CpuRayCaster::recycle(RenderResult&& spent) {
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
    const VolumeGeometry& g = volume_.geometry();
    const SamplingSettings& sampling = desc.sampling;
    const bool cubic = sampling.interpolation == Interpolation::Cubic;
    const bool exact = sampling.precision == Precision::Double;
    Cache& cache = *cache_;
    if (cubic && exact && cache.coefficientsD.empty()) {
        cache.coefficientsD = bsplineCoefficients<double>(volume_);
    }
    if (cubic && !exact && cache.coefficientsF.empty()) {
        cache.coefficientsF = bsplineCoefficients<float>(volume_);
    }
    auto gridFor = [&](int size, int overlap) -> const BrickGrid& {
        const auto key = std::tuple(size, cubic, overlap);
        auto it = cache.grids.find(key);
        if (it == cache.grids.end()) {
            if (cubic) {
                // Spline values are convex combinations of coefficients: their brick
                // min/max bound what a sample can see, the voxels' do not.
                Volume coef(g, VoxelType::Float32);
                const auto dst = coef.voxels<float>();
                for (std::size_t i = 0; i < dst.size(); ++i) {
                    dst[i] = exact ? float(cache.coefficientsD[i]) : cache.coefficientsF[i];
                }
                it = cache.grids.emplace(key, BrickGrid(coef, size, overlap)).first;
            } else {
                it = cache.grids.emplace(key, BrickGrid(volume_, size, overlap)).first;
            }
        }
        return it->second;
    };
    const BrickGrid& grid = gridFor(sampling.brickSize, 3);
    // Inside bricks that cannot be leapt, rays still leap over empty cells of this
    // size. The fast kernel's trilinear samples read their cell's voxels and one
    // beyond; a second voxel of overlap covers float rounding of positions.
    const bool fast = !exact && sampling.interpolation == Interpolation::Linear &&
                      desc.mode == RenderMode::Dvr && !sampling.preintegrate &&
                      sampling.classification == Classification::Post;
    const BrickGrid& cells = gridFor(std::min(sampling.brickSize, kLeapCell), fast ? 2 : 3);

    RaySetup<double> sd;
    RaySetup<float> sf;
    auto fill = [&](auto& s) {
        s.mode = desc.mode;
        s.classification = sampling.classification;
        s.preintegrate = sampling.preintegrate && desc.mode == RenderMode::Dvr;
        s.shading = desc.transferFunction.shading.enabled;
        s.exactTf = exact;
        s.tf = &desc.transferFunction;
        s.light = desc.transferFunction.shading;
        s.stepRatio = sampling.step;
        s.dt = sampling.step * std::min({g.spacing.x, g.spacing.y, g.spacing.z});
        s.earlyTermination = static_cast<decltype(s.earlyTermination)>(sampling.earlyTermination);
        s.isoValue = desc.isoValue;
        const glm::dmat3 linear(g.direction[0] * g.spacing.x, g.direction[1] * g.spacing.y,
                                g.direction[2] * g.spacing.z);
        s.gradientToWorld = glm::transpose(glm::inverse(linear)) /
                            gradientScale(cache.range.first, cache.range.second);
        s.boxLo = glm::dvec3(0.0);
        s.boxHi = glm::dvec3(g.dims - 1);
        s.clipLo = glm::max(desc.clip.lo, s.boxLo);
        s.clipHi = glm::min(desc.clip.hi, s.boxHi);
        if (part_) {
            // In the part's indices: the whole box anchors the lattice; the
            // part draws its owned box within the clip box.
            const glm::dvec3 offset(part_->offset);
            const glm::dvec3 wholeHi(part_->whole.dims - 1);
            s.part = true;
            s.boxLo = -offset;
            s.boxHi = wholeHi - offset;
            s.sceneClipLo = glm::max(desc.clip.lo, glm::dvec3(0.0)) - offset;
            s.sceneClipHi = glm::min(desc.clip.hi, wholeHi) - offset;
            s.clipLo = glm::max(s.sceneClipLo, glm::dvec3(part_->owned.lo) - offset);
            s.clipHi = glm::min(s.sceneClipHi, glm::dvec3(part_->owned.hi) - offset);
            for (int a = 0; a < 3; ++a) {
                s.openHi[a] = part_->sharedHi(a) && desc.clip.hi[a] >= double(part_->owned.hi[a]);
            }
        }
    };
    fill(sd);
    fill(sf);

    // Tables over the values a sample can take: the voxel range, or for cubic
    // the coefficient range (a spline can overshoot its samples).
    double tLo = cache.range.first, tHi = cache.range.second;
    if (cubic) {
        tLo = std::numeric_limits<double>::max();
        tHi = std::numeric_limits<double>::lowest();
        for (const Brick& b : grid.bricks()) {
            tLo = std::min(tLo, double(b.minValue));
            tHi = std::max(tHi, double(b.maxValue));
        }
    }
    std::tie(tLo, tHi) = tableRange(tLo, tHi);
    Cache::ClassificationKey key{
        desc.transferFunction, desc.mode,       desc.isoValue,   tLo,   tHi,
        sampling.step,         exact,           sf.preintegrate, cubic, grid.brickSize(),
        cells.brickSize(),     cells.overlap(),
    };
    const bool reuse = cache.key == key;
    if (!reuse) {
        cache.key.reset(); // until everything below is rebuilt
    }
    std::vector<glm::vec4>& rawTable = cache.rawTable;
    std::vector<glm::vec4>& table = cache.table;
    if (!exact) {
        if (!reuse) {
            rawTable = bakeTable(desc.transferFunction, tLo, tHi, kTableSize).rgba;
            table = rawTable;
            for (glm::vec4& e : table) {
                e.a = e.a <= 0.0f
                          ? 0.0f
                          : float(1.0 - std::pow(1.0 - std::min(double(e.a), 1.0), sampling.step));
            }
        }
        sf.rawTable = &rawTable;
        sf.table = &table;
        sf.tableLo = tLo;
        sf.tableScale = double(kTableSize - 1) / (tHi - tLo);
    }
    // Pre-integration: double precision integrates each segment exactly (the
    // reference), float looks segments up in a table.
    std::optional<SegmentPreintegrator> exactSegments;
    if (sf.preintegrate && exact) {
        sd.exactSegments = &exactSegments.emplace(desc.transferFunction, sampling.step);
    } else if (sf.preintegrate) {
        if (!reuse) {
            cache.preTable = buildPreintegrationTable(desc.transferFunction, tLo, tHi,
                                                      kPreintegrationSize, sampling.step);
        }
        sf.preTable = sd.preTable = &cache.preTable;
    }

    // Empty-space leaping: which bricks can be passed over, decided so that no
    // sample that could contribute is ever skipped.
    // (Widened by a cell of the table the samples are classified with.)
    const TransferFunction& tf = desc.transferFunction;
    const auto visible = valueVisibility(desc, tLo, tHi,
                                         exact             ? 0
                                         : sf.preintegrate ? kPreintegrationSize
                                                           : kTableSize);
    using LevelData = Cache::LevelData;
    auto levelData = [&](const BrickGrid& level) {
        LevelData out{std::vector<std::uint8_t>(level.count(), 0),
                      std::vector<glm::vec2>(level.count())};
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < level.count(); ++i) {
            const Brick& b = level.bricks()[i];
            out.skippable[i] = visible(b.minValue, b.maxValue) ? 0 : 1;
            // Voxel min/max bound trilinear and nearest samples exactly; coefficient
            // bounds went through float, so cubic keeps a margin.
            const double margin =
                cubic ? 1e-5 * (std::abs(b.minValue) + std::abs(b.maxValue) + 1.0) : 0.0;
            out.range[i] = glm::vec2(float(b.minValue - margin), float(b.maxValue + margin));
        }
        return out;
    };
    if (!reuse) {
        cache.coarse = levelData(grid);
        cache.fine = levelData(cells);
    }
    const LevelData &coarse = cache.coarse, &fine = cache.fine;
    // A fused render leaps (DVR only) where neither the base nor the overlay shows
    // (OverlayLeaping.h); MIP, MinIP and average with an overlay take every sample.
    const bool fusedDvr = overlay != nullptr && desc.mode == RenderMode::Dvr;
    const std::vector<std::uint8_t>* coarseSkip = &coarse.skippable;
    const std::vector<std::uint8_t>* fineSkip = &fine.skippable;
    if (fusedDvr && sampling.emptySpaceLeaping) {
        OverlayLeaping& o = cache.overlayLeaping;
        coarseSkip = &o.skippable(*overlay, desc.overlay.style, grid, coarse.skippable, 0);
        fineSkip = &o.skippable(*overlay, desc.overlay.style, cells, fine.skippable, 1);
    }
    auto setLevels = [&](auto& s) {
        s.leap = sampling.emptySpaceLeaping && (overlay == nullptr || fusedDvr);
        using Real = decltype(s.earlyTermination);
        s.levels[0] = {grid.brickSize(), Real(1) / Real(grid.brickSize()), grid.bricksPerAxis(),
                       coarseSkip, &coarse.range};
        s.levels[1] = {cells.brickSize(), Real(1) / Real(cells.brickSize()), cells.bricksPerAxis(),
                       fineSkip, &fine.range};
    };
    setLevels(sf);
    setLevels(sd);
    if (!reuse) {
        cache.cellLeap = leapCodes(grid, coarse.skippable, cells, fine.skippable);
        cache.reach = leapReach(cache.cellLeap, cells.bricksPerAxis());
        cache.leapReach.resize(cache.cellLeap.size());
        for (std::size_t i = 0; i < cache.cellLeap.size(); ++i) {
            cache.leapReach[i] = std::int32_t(cache.cellLeap[i]) | std::int32_t(cache.reach[i])
                                                                       << 8;
        }
        cache.key = std::move(key);
    }
    sf.cellLeap = &cache.cellLeap;
    sf.cellReach = &cache.reach;
    sf.cellLeapReach = &cache.leapReach;

    // Values outside the transfer function's non-zero opacity need no lookup.
    const double tableCell = exact ? 0.0 : (tHi - tLo) / double(kTableSize - 1);
    const auto [visLo, visHi] = visibleValueRange(tf, tableCell);
    sf.visibleLo = sd.visibleLo = visLo;
    sf.visibleHi = sd.visibleHi = visHi;
    // The fast kernels pass over samples in cells whose voxels all lie beyond
    // the visible range by more than the float rounding of a trilinear sample
    // (a table cell, or a few float ulps of the largest value).
    if (fast && (std::isfinite(visLo) || std::isfinite(visHi))) {
        const double margin = tableCell + 4e-6 * std::max(std::abs(tLo), std::abs(tHi));
        const std::pair bounds(sf.visibleLo - margin, sf.visibleHi + margin);
        if (cache.invisibleBounds != bounds) {
            cache.invisibleBounds.reset();
            cache.invisible = findInvisibleCells(volume_, bounds.first, bounds.second);
            cache.invisibleBounds = bounds;
        }
        sf.invisibleCells = &cache.invisible;
    }

    RenderResult result;
    recycledBuffers_ = cache.takeFrameBuffers(desc.width, desc.height, result);
    // A part draws its box in its own indices, over transparent black, seen as
    // the whole volume is.
    RenderDescription local = desc;
    if (part_) {
        local.clip = ClipBox{sf.clipLo, sf.clipHi};
        local.background = glm::dvec3(0.0);
    }
    result.stats.bricksTotal = grid.count();
    result.stats.bricksUsed = visibleBricks(grid, visible, local.clip).size();
    const ViewFrame frame =
        makeViewFrame(part_ ? part_->whole : g, desc.camera, desc.width, desc.height);

    // A part's projections are composited from their values (and counts).
    const bool projecting =
        part_ && (desc.mode == RenderMode::Mip || desc.mode == RenderMode::MinIp ||
                  desc.mode == RenderMode::Average);
    if (projecting) {
        result.projection.assign(result.premultiplied.size(), glm::vec2(0.0f));
    }
    auto cast = [&](const auto& kernel) {
        clock.timeCast([&] {
            castImage(kernel, g, frame, local, result.image, result.premultiplied,
                      result.stats.samples, projecting ? &result.projection : nullptr);
        });
    };
    // The overlay along the same rays (the generic kernel: the fast ones draw the base alone).
    const OverlayTable overlayEntries =
        overlay != nullptr ? overlayTable(desc.overlay.style, sampling.step) : OverlayTable{};
    auto castKernel = [&](const auto& setup, const auto& field) {
        using Real = decltype(setup.earlyTermination);
        using Field = std::remove_cvref_t<decltype(field)>;
        if (overlay == nullptr) {
            cast(RayKernel<Real, Field>(setup, field));
            return;
        }
        OverlaySampler<Real> sampler{
            LinearField<Real, float>{Grid<Real, float>(overlay->voxels<float>().data(), g.dims)},
            &overlayEntries, 0.0, 1.0};
        sampler.low = desc.overlay.style.center - 0.5 * desc.overlay.style.width;
        sampler.width = std::max(desc.overlay.style.width, 1e-9);
        cast(RayKernel<Real, Field, OverlaySampler<Real>>(setup, field, sampler));
    };
    auto run = [&](const auto& setup, auto tag) {
        using Real = decltype(tag);
        switch (sampling.interpolation) {
        case Interpolation::Cubic: {
            const Real* c = nullptr;
            if constexpr (std::is_same_v<Real, double>) {
                c = cache.coefficientsD.data();
            } else {
                c = cache.coefficientsF.data();
            }
            const CubicField<Real> field{Grid<Real, Real>(c, g.dims)};
            castKernel(setup, field);
            return;
        }
        case Interpolation::Nearest:
        case Interpolation::Linear:
            visitVoxels(volume_, [&](auto v) {
                using T = std::remove_const_t<typename decltype(v)::element_type>;
                const Grid<Real, T> grid(v.data(), g.dims);
                if (sampling.interpolation == Interpolation::Nearest) {
                    castKernel(setup, NearestField<Real, T>{grid});
                    return;
                }
                if constexpr (std::is_same_v<Real, float>) {
                    if (overlay == nullptr && sampling.simd && simdAllowed() &&
                        PacketDvrKernel<T>::applies(setup, g.dims)) {
                        cast(PacketDvrKernel<T>(setup, grid));
                        return;
                    }
                    if (overlay == nullptr && FastDvrKernel<T>::applies(setup, g.dims)) {
                        cast(FastDvrKernel<T>(setup, grid));
                        return;
                    }
                }
                castKernel(setup, LinearField<Real, T>{grid});
            });
            return;
        }
    };
    // A part whose box the clip box leaves out draws nothing.
    if (part_ && glm::any(glm::lessThan(sf.clipHi, sf.clipLo))) {
        result.stats.bricksUsed = 0;
        std::fill(result.image.pixels.begin(), result.image.pixels.end(), std::uint8_t(0));
        std::fill(result.premultiplied.begin(), result.premultiplied.end(), glm::vec4(0.0f));
        return result;
    }
    if (exact) {
        run(sd, double{});
    } else {
        run(sf, float{});
    }
    return result;
}

} // namespace lucent
