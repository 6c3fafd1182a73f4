#include "core/raycast/CpuCasterCache.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/raycast/BSplinePrefilter.h"
#include "core/raycast/BrickVisibility.h"
#include "core/raycast/LeapReach.h"

namespace lucent {

namespace {

constexpr int kTableSize = 4096;
constexpr int kPreintegrationSize = 256;
constexpr int kLeapCell = 8;

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

// Which bricks of `level` can be leapt, and their value bounds.
CpuCasterCache::LevelData
levelData(const BrickGrid& level, const std::function<bool(double, double)>& visible, bool cubic) {
    CpuCasterCache::LevelData out{std::vector<std::uint8_t>(level.count(), 0),
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
}

// The rays' settings from the description, in the volume's (or for a part,
// the part's) indices.
template <class Setup>
void describeRays(Setup& s, const RenderDescription& desc, const VolumeGeometry& g,
                  std::pair<double, double> range, const std::optional<VolumePart>& part) {
    const SamplingSettings& sampling = desc.sampling;
    s.mode = desc.mode;
    s.classification = sampling.classification;
    s.preintegrate = sampling.preintegrate && desc.mode == RenderMode::Dvr;
    s.shading = desc.transferFunction.shading.enabled;
    s.exactTf = sampling.precision == Precision::Double;
    s.tf = &desc.transferFunction;
    s.light = desc.transferFunction.shading;
    s.stepRatio = sampling.step;
    s.dt = sampling.step * std::min({g.spacing.x, g.spacing.y, g.spacing.z});
    s.earlyTermination = static_cast<decltype(s.earlyTermination)>(sampling.earlyTermination);
    s.isoValue = desc.isoValue;
    const glm::dmat3 linear(g.direction[0] * g.spacing.x, g.direction[1] * g.spacing.y,
                            g.direction[2] * g.spacing.z);
    s.gradientToWorld =
        glm::transpose(glm::inverse(linear)) / gradientScale(range.first, range.second);
    s.boxLo = glm::dvec3(0.0);
    s.boxHi = glm::dvec3(g.dims - 1);
    s.clipLo = glm::max(desc.clip.lo, s.boxLo);
    s.clipHi = glm::min(desc.clip.hi, s.boxHi);
    if (part) {
        // In the part's indices: the whole box anchors the lattice; the
        // part draws its owned box within the clip box.
        const glm::dvec3 offset(part->offset);
        const glm::dvec3 wholeHi(part->whole.dims - 1);
        s.part = true;
        s.boxLo = -offset;
        s.boxHi = wholeHi - offset;
        s.sceneClipLo = glm::max(desc.clip.lo, glm::dvec3(0.0)) - offset;
        s.sceneClipHi = glm::min(desc.clip.hi, wholeHi) - offset;
        s.clipLo = glm::max(s.sceneClipLo, glm::dvec3(part->owned.lo) - offset);
        s.clipHi = glm::min(s.sceneClipHi, glm::dvec3(part->owned.hi) - offset);
        for (int a = 0; a < 3; ++a) {
            s.openHi[a] = part->sharedHi(a) && desc.clip.hi[a] >= double(part->owned.hi[a]);
        }
    }
}

} // namespace

void CpuCasterCache::prepare(const Volume& volume, const std::optional<VolumePart>& part,
                             const RenderDescription& desc, CpuFrameSetup& frame) {
    const SamplingSettings& sampling = desc.sampling;
    const bool cubic = frame.cubic = sampling.interpolation == Interpolation::Cubic;
    const bool exact = frame.exact = sampling.precision == Precision::Double;
    if (cubic && exact && coefficientsD.empty()) {
        coefficientsD = bsplineCoefficients<double>(volume);
    }
    if (cubic && !exact && coefficientsF.empty()) {
        coefficientsF = bsplineCoefficients<float>(volume);
    }
    frame.grid = &gridFor(volume, sampling.brickSize, cubic, exact, 3);
    // Inside bricks that cannot be leapt, rays still leap over empty cells of this
    // size. The fast kernel's trilinear samples read their cell's voxels and one
    // beyond; a second voxel of overlap covers float rounding of positions.
    const bool fast = !exact && sampling.interpolation == Interpolation::Linear &&
                      desc.mode == RenderMode::Dvr && !sampling.preintegrate &&
                      sampling.classification == Classification::Post;
    frame.cells =
        &gridFor(volume, std::min(sampling.brickSize, kLeapCell), cubic, exact, fast ? 2 : 3);
    describeRays(frame.sd, desc, volume.geometry(), range, part);
    describeRays(frame.sf, desc, volume.geometry(), range, part);

    // Tables over the values a sample can take: the voxel range, or for cubic
    // the coefficient range (a spline can overshoot its samples).
    double tLo = range.first, tHi = range.second;
    if (cubic) {
        tLo = std::numeric_limits<double>::max();
        tHi = std::numeric_limits<double>::lowest();
        for (const Brick& b : frame.grid->bricks()) {
            tLo = std::min(tLo, double(b.minValue));
            tHi = std::max(tHi, double(b.maxValue));
        }
    }
    std::tie(tLo, tHi) = tableRange(tLo, tHi);
    ClassificationKey wanted{
        desc.transferFunction,
        desc.mode,
        desc.isoValue,
        tLo,
        tHi,
        sampling.step,
        exact,
        frame.sf.preintegrate,
        cubic,
        frame.grid->brickSize(),
        frame.cells->brickSize(),
        frame.cells->overlap(),
    };
    const bool reuse = key == wanted;
    if (!reuse) {
        key.reset(); // until everything below is rebuilt
    }
    const double tableCell = classify(desc, reuse, tLo, tHi, frame);
    // Empty-space leaping: which bricks can be passed over, decided so that no
    // sample that could contribute is ever skipped (widened by a cell of the
    // table the samples are classified with).
    frame.visible = valueVisibility(desc, tLo, tHi,
                                    exact                   ? 0
                                    : frame.sf.preintegrate ? kPreintegrationSize
                                                            : kTableSize);
    leapLevels(desc, reuse, frame);
    if (!reuse) {
        key = std::move(wanted);
    }
    findInvisible(volume, desc.transferFunction, tableCell, tLo, tHi, fast, frame);
}

const BrickGrid& CpuCasterCache::gridFor(const Volume& volume, int size, bool cubic, bool exact,
                                         int overlap) {
    const auto wanted = std::tuple(size, cubic, overlap);
    auto it = grids.find(wanted);
    if (it == grids.end()) {
        if (cubic) {
            // Spline values are convex combinations of coefficients: their brick
            // min/max bound what a sample can see, the voxels' do not.
            Volume coef(volume.geometry(), VoxelType::Float32);
            const auto dst = coef.voxels<float>();
            for (std::size_t i = 0; i < dst.size(); ++i) {
                dst[i] = exact ? float(coefficientsD[i]) : coefficientsF[i];
            }
            it = grids.emplace(wanted, BrickGrid(coef, size, overlap)).first;
        } else {
            it = grids.emplace(wanted, BrickGrid(volume, size, overlap)).first;
        }
    }
    return it->second;
}

double CpuCasterCache::classify(const RenderDescription& desc, bool reuse, double tLo, double tHi,
                                CpuFrameSetup& frame) {
    const SamplingSettings& sampling = desc.sampling;
    RaySetup<float>& sf = frame.sf;
    if (!frame.exact) {
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
    if (sf.preintegrate && frame.exact) {
        frame.sd.exactSegments = &frame.exactSegments.emplace(desc.transferFunction, sampling.step);
    } else if (sf.preintegrate) {
        if (!reuse) {
            preTable = buildPreintegrationTable(desc.transferFunction, tLo, tHi,
                                                kPreintegrationSize, sampling.step);
        }
        sf.preTable = frame.sd.preTable = &preTable;
    }
    return frame.exact ? 0.0 : (tHi - tLo) / double(kTableSize - 1);
}

void CpuCasterCache::leapLevels(const RenderDescription& desc, bool reuse, CpuFrameSetup& frame) {
    const BrickGrid &grid = *frame.grid, &cells = *frame.cells;
    if (!reuse) {
        coarse = levelData(grid, frame.visible, frame.cubic);
        fine = levelData(cells, frame.visible, frame.cubic);
    }
    // A fused render leaps (DVR only) where neither the base nor the overlay shows
    // (OverlayLeaping.h); MIP, MinIP and average with an overlay take every sample.
    const Volume* overlay = desc.overlay.volume;
    const bool fusedDvr = overlay != nullptr && desc.mode == RenderMode::Dvr;
    const std::vector<std::uint8_t>* coarseSkip = &coarse.skippable;
    const std::vector<std::uint8_t>* fineSkip = &fine.skippable;
    if (fusedDvr && desc.sampling.emptySpaceLeaping) {
        coarseSkip =
            &overlayLeaping.skippable(*overlay, desc.overlay.style, grid, coarse.skippable, 0);
        fineSkip =
            &overlayLeaping.skippable(*overlay, desc.overlay.style, cells, fine.skippable, 1);
    }
    auto setLevels = [&](auto& s) {
        s.leap = desc.sampling.emptySpaceLeaping && (overlay == nullptr || fusedDvr);
        using Real = decltype(s.earlyTermination);
        s.levels[0] = {grid.brickSize(), Real(1) / Real(grid.brickSize()), grid.bricksPerAxis(),
                       coarseSkip, &coarse.range};
        s.levels[1] = {cells.brickSize(), Real(1) / Real(cells.brickSize()), cells.bricksPerAxis(),
                       fineSkip, &fine.range};
    };
    setLevels(frame.sf);
    setLevels(frame.sd);
    if (!reuse) {
        cellLeap = leapCodes(grid, coarse.skippable, cells, fine.skippable);
        reach = lucent::leapReach(cellLeap, cells.bricksPerAxis());
        leapReach.resize(cellLeap.size());
        for (std::size_t i = 0; i < cellLeap.size(); ++i) {
            leapReach[i] = std::int32_t(cellLeap[i]) | std::int32_t(reach[i]) << 8;
        }
    }
    frame.sf.cellLeap = &cellLeap;
    frame.sf.cellReach = &reach;
    frame.sf.cellLeapReach = &leapReach;
}

void CpuCasterCache::findInvisible(const Volume& volume, const TransferFunction& tf,
                                   double tableCell, double tLo, double tHi, bool fast,
                                   CpuFrameSetup& frame) {
    RaySetup<float>& sf = frame.sf;
    // Values outside the transfer function's non-zero opacity need no lookup.
    const auto [visLo, visHi] = visibleValueRange(tf, tableCell);
    sf.visibleLo = frame.sd.visibleLo = visLo;
    sf.visibleHi = frame.sd.visibleHi = visHi;
    // The fast kernels pass over samples in cells whose voxels all lie beyond
    // the visible range by more than the float rounding of a trilinear sample
    // (a table cell, or a few float ulps of the largest value).
    if (fast && (std::isfinite(visLo) || std::isfinite(visHi))) {
        const double margin = tableCell + 4e-6 * std::max(std::abs(tLo), std::abs(tHi));
        const std::pair bounds(sf.visibleLo - margin, sf.visibleHi + margin);
        if (invisibleBounds != bounds) {
            invisibleBounds.reset();
            invisible = findInvisibleCells(volume, bounds.first, bounds.second);
            invisibleBounds = bounds;
        }
        sf.invisibleCells = &invisible;
    }
}

bool CpuCasterCache::takeFrameBuffers(int width, int height, RenderResult& r) {
    const std::size_t n = std::size_t(width) * std::size_t(height);
    const bool spare = spareImage.width == width && spareImage.height == height &&
                       spareImage.pixels.size() == 4 * n && sparePremultiplied.size() == n;
    if (spare) {
        r.image = std::move(spareImage);
        r.premultiplied = std::move(sparePremultiplied);
    } else {
        r.image = ImageRGBA8::filled(width, height, 0);
        r.premultiplied.assign(n, glm::vec4(0.0f));
    }
    spareImage = ImageRGBA8{};
    sparePremultiplied = {};
    return spare;
}

} // namespace lucent
