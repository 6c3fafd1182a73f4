#pragma once
// What CpuRayCaster keeps between frames and how a frame's rays are set up
// from it: B-spline coefficients, brick grids, the classification (tables,
// leap levels and codes, invisible cells) kept while what it depends on stays
// the same, and a handed-back frame's buffers. Private to core/raycast.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "core/image/Image.h"
#include "core/raycast/InvisibleCells.h"
#include "core/raycast/OverlayLeaping.h"
#include "core/raycast/RaySetup.h"
#include "core/scene/Renderer.h"
#include "core/tf/TransferFunction.h"
#include "core/volume/BrickGrid.h"
#include "core/volume/VolumePart.h"

namespace lucent {

// A frame's rays in both precisions, and what they were set up from. Not
// copyable: sd.exactSegments points into it.
struct CpuFrameSetup {
    RaySetup<double> sd;
    RaySetup<float> sf;
    const BrickGrid* grid = nullptr;  // the leaping bricks
    const BrickGrid* cells = nullptr; // the leap cells within them
    bool cubic = false, exact = false;
    // valueVisibility of the frame: which value ranges can show.
    std::function<bool(double lo, double hi)> visible;
    std::optional<SegmentPreintegrator> exactSegments;

    CpuFrameSetup() = default;
    CpuFrameSetup(const CpuFrameSetup&) = delete;
    CpuFrameSetup& operator=(const CpuFrameSetup&) = delete;
};

struct CpuCasterCache {
    std::pair<double, double> range{0.0, 0.0};
    std::vector<float> coefficientsF;
    std::vector<double> coefficientsD;
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

    // Sets up `frame`'s rays for `desc` (validated, of `volume`, a part when
    // `part` is set), rebuilding only what `desc` changed since the last frame.
    void prepare(const Volume& volume, const std::optional<VolumePart>& part,
                 const RenderDescription& desc, CpuFrameSetup& frame);
    // The frame's image and premultiplied colours: the spare ones when their
    // size matches (returns true), else new ones. castImage writes every pixel
    // of both (premultiplied 0 where no ray is cast), so spare ones are not cleared.
    bool takeFrameBuffers(int width, int height, RenderResult& r);

private:
    const BrickGrid& gridFor(const Volume& volume, int size, bool cubic, bool exact, int overlap);
    // Tables (float) or segments (pre-integration); returns the table cell.
    double classify(const RenderDescription& desc, bool reuse, double tLo, double tHi,
                    CpuFrameSetup& frame);
    void leapLevels(const RenderDescription& desc, bool reuse, CpuFrameSetup& frame);
    void findInvisible(const Volume& volume, const TransferFunction& tf, double tableCell,
                       double tLo, double tHi, bool fast, CpuFrameSetup& frame);
};

} // namespace lucent
