#pragma once
// What of a volume the GPU holds for a frame, within a budget: for every
// level-0 brick the scene can see, the box of its voxels the transfer function
// and clip box leave visible (core/volume/BrickBoxes.h), at the level of detail
// the budget allows for it (core/volume/BrickLevels.h), in an atlas of boxes
// (BrickPool). The pool's bricks are pages of at most kPageSize voxels a side
// (a brick of 64 is eight pages): boxes fit what is visible more tightly
// than whole bricks (measured on a CT with CT-Bone: 44 % of the voxels
// against 55 %), for a page table eight times larger. Bricks stream in: a frame uploads what is
// missing, within an upload cap when one is set, and shows a brick not yet uploaded at its planned
// level from a coarser level it already holds. Private to render/.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/raycast/BrickVisibility.h"
#include "core/volume/BrickBoxes.h"
#include "core/volume/BrickLevels.h"
#include "core/volume/LodPyramid.h"
#include "render/BrickPlacement.h"
#include "render/BrickPool.h"
#include "render/BrickTable.h"

namespace lucent {

struct BrickRequest {
    int brickSize = 64;
    bool cubic = false;                 // the pool holds B-spline coefficients
    bool halfFloat = false;             // ... in 16-bit floats
    bool shaded = false;                // samples read gradients
    bool gradientCache = true;          // keep them in the pool when they fit (not cubic)
    std::size_t gradientCacheBytes = 0; // ... and the bricks with them take at most this (0: any)
    double gradientUnit = 1.0;          // value units of a cached gradient component of 1 (int16)
    std::function<bool(double, double)> visible;
    // What `visible` answers from (equal keys, equal answers): the cell masks
    // and boxes built for one request serve the next with the same key, clip
    // box, filter and page size.
    VisibilityKey visibilityKey;
    bool decides = true;         // DVR, iso: visibility decides what is leapt
    bool withNeighbours = false; // pre-integration, iso: rays read next to visible cells
    ClipBox clip;                // level-0 indices
    // Whether a box of level-0 voxel centres can be seen; how much a brick's
    // refinement is worth (BrickCandidate::worth), from its box.
    std::function<bool(const glm::dvec3&, const glm::dvec3&)> inView;
    std::function<double(const glm::dvec3&, const glm::dvec3&, double content)> worth;
    LodPolicy policy = LodPolicy::PerBrick;
    std::size_t uploadCap = 0; // bytes a frame may upload beyond what it must; 0: no cap
    bool tight = true;         // false: whole pages wherever any cell shows (to compare against)
};

struct BrickFrameStats {
    std::size_t bricksUploaded = 0, bytesUploaded = 0;
    std::size_t bricksShown = 0, bricksNeeded = 0; // pages
    std::size_t bricksTotal = 0, bricksUsed = 0;   // of the asked brick size
    std::size_t pending = 0; // bricks shown coarser than planned (still streaming)
    std::size_t valueBytes = 0, gradientBytes = 0, tableBytes = 0; // resident
    std::size_t poolBytes = 0;
    std::vector<std::size_t> perLevel;     // bricks shown per level
    std::vector<std::int8_t> levelOfBrick; // per page: the level it is drawn from, -1 none
    int brickSize = 0;                     // of the pages
    int finestLevel = 0, coarsestLevel = 0;
    bool gradientsCached = false;
    std::string lodReason;
    // What this frame built anew: the levels whose cell masks and boxes it
    // classified (0: all cached), and whether it planned the octree, the level
    // choice and the page table (false: the last frame's held, only the camera moved).
    int levelsClassified = 0;
    bool planned = false;
};

class BrickOctree;

class BrickStreamer {
public:
    static constexpr int kPageSize = 32;

    // `budget` bytes for the pool's textures (values and gradients).
    BrickStreamer(const Volume& volume, std::size_t budget);

    // Makes the frame's bricks resident and returns the table the shader reads.
    // Throws BudgetError when not even the coarsest level fits, GlError when
    // the driver refuses.
    const BrickTable& update(const BrickRequest& request, BrickFrameStats& stats);

    const BrickPool& pool() const { return *pool_; }
    // Counts the page tables built: equal counts, the same table.
    std::uint64_t tableGeneration() const { return tableGeneration_; }
    // Each level's dimensions (at most 8 levels).
    std::vector<glm::ivec3> levelDims();
    // The value range the tables cover: the voxels', or the spline coefficients'.
    std::pair<double, double> valueRange(bool cubic, int brickSize);
    // The pool's format for the volume's voxels or the coefficients.
    TexelFormat format(bool cubic, bool halfFloat) const;

private:
    using LevelBoxList = std::vector<std::optional<SampleBox>>;
    // What the cell masks and boxes depend on (not the camera).
    struct BoxKey {
        VisibilityKey visibility;
        ClipBox clip;
        int pageSize = 0;
        bool cubic = false, withNeighbours = false;
        bool operator==(const BoxKey&) const = default;
    };
    struct LevelBoxes {
        std::vector<std::uint8_t> cells; // per level-0 cell: visible at this level
        LevelBoxList boxes;              // per page, before the view culls them
    };
    // What a frame's plan depends on besides the camera's pages in view.
    struct FrameKey {
        std::uint64_t boxes = 0; // boxGeneration_
        std::vector<char> inView;
        std::size_t budget = 0;
        LodPolicy policy = LodPolicy::PerBrick;
        std::size_t uploadCap = 0;
        bool shaded = false, gradientCache = false, halfFloat = false, decides = false,
             gradientsRefused = false;
        std::size_t gradientCacheBytes = 0;
        int brickSize = 0;
        double gradientUnit = 0.0;
        bool tight = true;
        bool operator==(const FrameKey&) const = default;
    };

    // update() with the boxes' bytes limited to `budget`.
    const BrickTable& updateWithin(const BrickRequest& r, BrickFrameStats& stats,
                                   std::size_t budget);
    // Builds a level's cell masks and boxes unless cached for r's key; 1 when built.
    int classify(const BrickRequest& r, int level);
    std::vector<double> pageContents(const BrickRequest& r, const std::vector<std::uint8_t>& cells);
    LevelBoxList boxesInView(const BrickRequest& r, int level) const;
    FrameKey frameKey(const BrickRequest& r, std::size_t budget, const LevelBoxList& inView) const;
    std::vector<Shown> showNodes(const BrickOctree& tree, const LevelChoice& choice,
                                 FilterReach reach, bool gradients, std::size_t uploadCap,
                                 BrickFrameStats& st) const;
    void upload(const std::vector<Shown>& shown, const BrickRequest& r, BrickFrameStats& st);
    void makeTable(const BrickOctree& tree, const std::vector<Shown>& shown,
                   const std::vector<LevelBoxList>& perLevel, const BrickRequest& r,
                   BrickFrameStats& st);
    void countResident(BrickFrameStats& st) const;
    const Volume& source(int level, bool cubic);
    const BrickGrid& grid(int brickSize, bool cubic, int level, int overlap = 3);
    const std::vector<std::uint32_t>& levelCells(bool cubic, int level);
    int levelCount();
    void ensurePool(const BrickRequest& r, bool gradients, std::size_t needBytes,
                    glm::ivec3 largest);

    const Volume& volume_;
    std::size_t budget_;
    double packing_ = 0.9; // of the budget the boxes may take (lowered where they do not pack)
    std::unique_ptr<LodPyramid> pyramid_;
    std::map<int, std::unique_ptr<Volume>> splines_;
    std::map<std::tuple<int, bool, int, int>, std::unique_ptr<BrickGrid>> grids_;
    std::map<std::tuple<bool, int>, std::vector<std::uint32_t>> levelCells_; // per level-0 cell
    std::unique_ptr<BrickBoxes> boxes_;
    std::unique_ptr<BrickPool> pool_;
    std::tuple<int, bool, bool> poolKind_{0, false, false};
    bool gradientsRefused_ = false;
    std::uint64_t frame_ = 0;
    BrickTable table_;
    std::uint64_t tableGeneration_ = 0;
    // Cached for the transfer function, clip box and filter (boxKey_): per
    // level, built when first needed; per page, what it shows.
    std::optional<BoxKey> boxKey_;
    std::vector<std::optional<LevelBoxes>> levelBoxes_;
    std::vector<double> pageContent_;
    std::uint64_t boxGeneration_ = 0;
    // The last frame's key where its plan holds for any camera with that key,
    // the nodes it showed and its statistics.
    std::optional<FrameKey> reusable_;
    std::vector<std::pair<int, std::uint32_t>> lastShown_;
    BrickFrameStats lastStats_;
};

} // namespace lucent
