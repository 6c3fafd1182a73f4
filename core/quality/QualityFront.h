#pragma once
// The speed/accuracy trade, measured: a sweep of sampling settings, each with
// its time per frame and its error against the reference, and the settings on
// the front (none faster and more accurate at once). Renderer-agnostic: the
// caller renders.

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/raycast/CpuRayCaster.h"
#include "core/scene/RenderDescription.h"

namespace lucent {

struct QualitySetting {
    double step = 0.5;
    Interpolation interpolation = Interpolation::Linear;
    Classification classification = Classification::Post;
    bool preintegrate = false;
    bool shading = true;
    int brickSize = 64;

    // "post", "pre" or "preintegrated".
    std::string classificationName() const;
    // The description with these settings (shading switches the TF's shading).
    RenderDescription applyTo(const RenderDescription& d) const;
};

struct QualityPoint {
    QualitySetting setting;
    double ms = 0.0; // median time per frame
    std::size_t samples = 0;
    double psnrDb = 0.0;
    double ssim = 0.0;
    bool pareto = false;
};

// The sweep of the quality bench: every step in `steps` x nearest/linear/cubic
// x post/pre/pre-integrated x shading on/off x every brick size.
// Pre-classification is swept with trilinear interpolation only: nearest
// classifies the voxel it picks anyway, and the renderers define it for the
// trilinear neighbourhood.
std::vector<QualitySetting> qualitySweep(const std::vector<double>& steps,
                                         const std::vector<int>& brickSizes);

// The reference every point is measured against: double precision, tricubic,
// step 1/16 voxel, no early termination.
RenderDescription qualityReference(const RenderDescription& d);

// Sets `pareto` on the points no other point with the same shading beats in
// both time (lower) and PSNR (higher); ties in both keep both. Shaded and
// unshaded images are measured against different references, so each has its
// own front.
void markParetoFront(std::vector<QualityPoint>& points);

// The most accurate point of the front (of that shading) within `ms` per
// frame; the fastest point when none is that fast; nullopt for no points.
std::optional<QualityPoint> bestWithin(const std::vector<QualityPoint>& points, double ms,
                                       bool shading);

// The reduced sweep of a quick front, around the settings the full fronts put
// on the front (docs/quality): steps 2, 1, 0.5 and 0.25 voxels with trilinear
// and tricubic, nearest at step 2, post-classified; pre-integrated trilinear
// at steps 2, 1 and 0.5; bricks of 64; the given shading only.
std::vector<QualitySetting> quickSweep(bool shading);

// Renders one frame with the renderer being measured.
using QualityRender = std::function<RenderResult(const RenderDescription&)>;

// One warm-up frame, then the median time in ms of `frames` frames (more, up
// to 4 * frames, until they took `minTotalMs`); the last frame in `last`.
double timeFrames(const QualityRender& render, const RenderDescription& description, int frames,
                  double minTotalMs, RenderResult& last);

// Measures each setting on `base`: one warm-up frame, then the median time of
// `frames` frames (more, up to 4 * frames, until they took `minTotalMs`: short
// frames need more to outvote a stall), the samples, and PSNR and SSIM against
// `reference`'s image of qualityReference() (rendered once per shading
// state); marks the front. `progress(done, total)` is called after each
// setting when given.
std::vector<QualityPoint>
measureQuality(const RenderDescription& base, const std::vector<QualitySetting>& settings,
               const QualityRender& render, const QualityRender& reference, int frames,
               const std::function<void(std::size_t, std::size_t)>& progress = {},
               double minTotalMs = 0.0);

// The bench's CSV: header (no newline) and one row per point (with newline).
std::string qualityCsvHeader();
std::string qualityCsvRow(const QualityPoint& p);
// Reads a row written by qualityCsvRow; throws std::invalid_argument naming
// the column that does not parse.
QualityPoint parseQualityCsvRow(const std::string& row);

} // namespace lucent
