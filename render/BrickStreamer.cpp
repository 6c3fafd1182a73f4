#include "render/BrickStreamer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/raycast/BSplinePrefilter.h"
#include "render/BrickOctree.h"
#include "render/BrickPlacement.h"
#include "render/GlError.h"

namespace lucent {

namespace {

constexpr int kCellSize = 8;    // the leaping cells (as on the CPU)
constexpr int kGridOverlap = 3; // cell ranges cover every filter's reach at their level

using LevelBoxList = std::vector<std::optional<SampleBox>>;

std::size_t bytesOf(const LevelBoxList& boxes, int level, FilterReach reach,
                    std::size_t texelBytes) {
    std::size_t sum = 0;
    for (const auto& box : boxes) {
        sum += box ? volumeOf(storedBox(*box, level, reach).size) * texelBytes : 0;
    }
    return sum;
}

} // namespace

BrickStreamer::BrickStreamer(const Volume& volume, std::size_t budget)
    : volume_(volume), budget_(budget) {}

TexelFormat BrickStreamer::format(bool cubic, bool halfFloat) const {
    if (cubic || volume_.type() == VoxelType::Float32) {
        return halfFloat && cubic ? TexelFormat{GL_R16F, GL_FLOAT, 4, 2, 1.0f}
                                  : TexelFormat{GL_R32F, GL_FLOAT, 4, 4, 1.0f};
    }
    if (volume_.type() == VoxelType::UInt16) {
        return {GL_R16, GL_UNSIGNED_SHORT, 2, 2, 65535.0f};
    }
    return {GL_R16_SNORM, GL_SHORT, 2, 2, 32767.0f};
}

int BrickStreamer::levelCount() {
    if (!pyramid_) {
        pyramid_ = std::make_unique<LodPyramid>(volume_);
    }
    return pyramid_->levelCount();
}

const Volume& BrickStreamer::source(int level, bool cubic) {
    const Volume& v = level == 0 ? volume_ : (levelCount(), pyramid_->level(level));
    if (!cubic) {
        return v;
    }
    auto& s = splines_[level];
    if (!s) {
        s = std::make_unique<Volume>(v.geometry(), VoxelType::Float32);
        const std::vector<float> c = bsplineCoefficients<float>(v);
        std::copy(c.begin(), c.end(), s->voxels<float>().begin());
    }
    return *s;
}

const BrickGrid& BrickStreamer::grid(int brickSize, bool cubic, int level, int overlap) {
    auto& g = grids_[{brickSize, cubic, level, overlap}];
    if (!g) {
        g = std::make_unique<BrickGrid>(source(level, cubic), brickSize, overlap);
    }
    return *g;
}

const std::vector<std::uint32_t>& BrickStreamer::levelCells(bool cubic, int level) {
    auto& at = levelCells_[{cubic, level}];
    if (at.empty()) {
        at = boxes_->levelCellOf(grid(kCellSize, cubic, level), level);
    }
    return at;
}

std::vector<glm::ivec3> BrickStreamer::levelDims() {
    std::vector<glm::ivec3> dims{volume_.dims()};
    for (int l = 1; pyramid_ && l < pyramid_->levelCount(); ++l) {
        dims.push_back(pyramid_->level(l).dims());
    }
    return dims;
}

std::pair<double, double> BrickStreamer::valueRange(bool cubic, int brickSize) {
    if (!cubic) {
        return volume_.valueRange();
    }
    double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
    for (const Brick& b : grid(brickSize, true, 0).bricks()) {
        lo = std::min(lo, double(b.minValue));
        hi = std::max(hi, double(b.maxValue));
    }
    return {lo, hi};
}

void BrickStreamer::ensurePool(const BrickRequest& r, bool gradients, std::size_t needBytes,
                               glm::ivec3 largest) {
    const TexelFormat f = format(r.cubic, r.halfFloat);
    const std::tuple kind(r.brickSize, r.cubic, gradients);
    if (pool_ && poolKind_ == kind) {
        return;
    }
    pool_.reset(); // another content: nothing resident can be used
    const std::size_t texelBytes = BrickPool::texelBytes(f, gradients);
    const std::size_t texels =
        std::min((needBytes + needBytes / 8) / texelBytes + 1, budget_ / texelBytes);
    GLint maxSide = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSide);
    pool_ = std::make_unique<BrickPool>(
        f, gradients, BoxAtlas::extentFor(texels, largest, int(maxSide), budget_ / texelBytes));
    poolKind_ = kind;
}

const BrickTable& BrickStreamer::update(const BrickRequest& r, BrickFrameStats& st) {
    // The boxes may take a share of the budget: the atlas needs room to pack
    // them. Where they do not pack, the levels are chosen again for less.
    for (;;) {
        try {
            return updateWithin(r, st, std::size_t(double(budget_) * packing_));
        } catch (const PackingError& e) {
            reusable_.reset();
            if (packing_ < 0.35) {
                throw BudgetError(e.what());
            }
            packing_ -= 0.1;
        }
    }
}

int BrickStreamer::classify(const BrickRequest& r, int level) {
    BoxKey key{r.visibilityKey, r.clip, boxes_->brickSize(), r.cubic, r.withNeighbours};
    if (!boxKey_ || !(*boxKey_ == key)) {
        boxKey_ = std::move(key);
        levelBoxes_.clear();
        pageContent_.clear();
        ++boxGeneration_;
    }
    if (levelBoxes_.size() > std::size_t(level) && levelBoxes_[std::size_t(level)]) {
        return 0;
    }
    levelBoxes_.resize(std::max(levelBoxes_.size(), std::size_t(level) + 1));
    // Level 0's trilinear samples in a cell read only its voxels and the
    // next (an overlap of 1 decides what they can show); a coarser level's
    // cells answer for level-0 cells through their overlap of 3.
    const int overlap = level == 0 && !r.cubic ? 1 : kGridOverlap;
    LevelBoxes& lb = levelBoxes_[std::size_t(level)].emplace();
    lb.cells =
        boxes_->visibleCells(grid(kCellSize, r.cubic, level, overlap), level, r.visible, r.clip);
    lb.boxes = boxes_->boxes(lb.cells, r.withNeighbours);
    if (level == 0) {
        pageContent_ = pageContents(r, lb.cells);
    }
    return 1;
}

std::vector<double> BrickStreamer::pageContents(const BrickRequest& r,
                                                const std::vector<std::uint8_t>& cells) {
    // What a page shows: its visible cells at level 0, and above all those
    // where a surface passes (values on both sides of what the transfer
    // function shows): there coarser voxels blur what is drawn.
    const int pageSize = boxes_->brickSize();
    const int cellsPerPage = std::max(1, pageSize / kCellSize);
    const glm::ivec3 cp = boxes_->cellsPerAxis();
    const BrickGrid& cells0 = grid(kCellSize, r.cubic, 0);
    std::vector<double> content(boxes_->brickCount(), 0.0);
    for (std::uint32_t b = 0; b < boxes_->brickCount(); ++b) {
        const glm::ivec3 lo = boxes_->brickIndex(b) * pageSize;
        const glm::ivec3 hi = glm::min(lo + pageSize, volume_.dims());
        double shows = 0.0;
        for (int z = lo.z / kCellSize; z * kCellSize < hi.z; ++z) {
            for (int y = lo.y / kCellSize; y * kCellSize < hi.y; ++y) {
                for (int x = lo.x / kCellSize; x * kCellSize < hi.x; ++x) {
                    const std::size_t c =
                        std::size_t(x) +
                        std::size_t(cp.x) * (std::size_t(y) + std::size_t(cp.y) * z);
                    if (cells[c] == 0) {
                        continue;
                    }
                    const Brick& range = cells0.bricks()[c];
                    const bool surface = !r.visible(range.minValue, range.minValue) ||
                                         !r.visible(range.maxValue, range.maxValue);
                    shows += surface ? 1.0 : 0.25;
                }
            }
        }
        content[b] = std::sqrt((shows + 0.1) / (std::pow(double(cellsPerPage), 3.0) + 0.1));
    }
    return content;
}

std::vector<std::optional<SampleBox>> BrickStreamer::boxesInView(const BrickRequest& r,
                                                                 int level) const {
    std::vector<std::optional<SampleBox>> boxes = levelBoxes_[std::size_t(level)]->boxes;
    for (std::size_t b = 0; b < boxes.size(); ++b) {
        auto& box = boxes[b];
        if (box && r.inView && !r.inView(glm::dvec3(box->lo), glm::dvec3(box->hi - 1))) {
            box.reset();
        }
        if (box && !r.tight) { // the whole page, as bricks were before boxes
            box->lo = boxes_->brickIndex(b) * boxes_->brickSize();
            box->hi = glm::min(box->lo + boxes_->brickSize(), volume_.dims());
        }
    }
    return boxes;
}

BrickStreamer::FrameKey BrickStreamer::frameKey(const BrickRequest& r, std::size_t budget,
                                                const LevelBoxList& inView) const {
    FrameKey key;
    key.boxes = boxGeneration_;
    key.budget = budget;
    key.policy = r.policy;
    key.uploadCap = r.uploadCap;
    key.shaded = r.shaded;
    key.gradientCache = r.gradientCache;
    key.halfFloat = r.halfFloat;
    key.decides = r.decides;
    key.gradientsRefused = gradientsRefused_;
    key.gradientCacheBytes = r.gradientCacheBytes;
    key.brickSize = r.brickSize;
    key.gradientUnit = r.gradientUnit;
    key.tight = r.tight;
    key.inView.reserve(inView.size());
    for (const auto& box : inView) {
        key.inView.push_back(box.has_value() ? 1 : 0);
    }
    return key;
}

const BrickTable& BrickStreamer::updateWithin(const BrickRequest& r, BrickFrameStats& st,
                                              std::size_t budget) {
    ++frame_;
    const int pageSize = std::min(r.brickSize, kPageSize);
    if (!boxes_ || boxes_->brickSize() != pageSize) {
        boxes_ = std::make_unique<BrickBoxes>(volume_.dims(), pageSize, kCellSize);
        boxKey_.reset();
    }
    int classified = classify(r, 0);
    std::vector<LevelBoxList> perLevel{boxesInView(r, 0)};
    FrameKey key = frameKey(r, budget, perLevel[0]);
    if (reusable_ && *reusable_ == key) {
        // Only the camera moved, and every brick it shows was resident at
        // level 0 already: the last frame's table holds.
        for (const auto& [level, id] : lastShown_) {
            pool_->touch(level, id, frame_);
        }
        st = lastStats_;
        st.bricksUploaded = st.bytesUploaded = 0;
        st.levelsClassified = 0;
        st.planned = false;
        return table_;
    }
    const TexelFormat f = format(r.cubic, r.halfFloat);
    const FilterReach computed = filterReach(r.cubic, r.shaded);
    const FilterReach cached = filterReach(r.cubic, false);
    const std::size_t valuesOnly = BrickPool::texelBytes(f, false);
    // Coarser levels where level 0 does not fit, or to stand in while bricks stream.
    if (bytesOf(perLevel[0], 0, computed, valuesOnly) > budget || r.uploadCap > 0) {
        for (int level = 1; level < levelCount(); ++level) {
            classified += classify(r, level);
            perLevel.push_back(boxesInView(r, level));
        }
    }
    std::vector<double> worth(boxes_->brickCount(), 0.0);
    for (std::uint32_t b = 0; b < boxes_->brickCount(); ++b) {
        const glm::ivec3 lo = boxes_->brickIndex(b) * pageSize;
        const glm::ivec3 hi = glm::min(lo + pageSize, volume_.dims());
        worth[b] = r.worth ? r.worth(glm::dvec3(lo), glm::dvec3(hi - 1), pageContent_[b])
                           : pageContent_[b];
    }
    const BrickOctree tree(*boxes_, perLevel, worth);
    LevelChoice choice = tree.choose(computed, valuesOnly, budget, r.policy);
    // Gradients are cached when they cost no brick a finer level, and the
    // bricks with them stay within their share of memory.
    bool gradients = false;
    const bool mayCache = r.shaded && r.gradientCache && !r.cubic && !gradientsRefused_;
    if (mayCache || (pool_ && pool_->hasGradients() && !r.cubic)) {
        try {
            const LevelChoice with =
                tree.choose(cached, BrickPool::texelBytes(f, true), budget, r.policy);
            const bool withinShare =
                r.gradientCacheBytes == 0 || with.bytes <= r.gradientCacheBytes;
            if (with.shown == choice.shown && withinShare) {
                choice = with;
                gradients = true;
            }
        } catch (const BudgetError&) {
            // not even the levels tried hold them: computed gradients
        }
    }
    const FilterReach reach = gradients ? cached : computed;
    if (!pool_ || poolKind_ != std::tuple(r.brickSize, r.cubic, gradients)) {
        glm::ivec3 largest(1);
        for (const std::size_t n : choice.shown) {
            if (const auto& box = tree.nodes()[n].box) {
                largest = glm::max(largest, storedBox(*box, tree.nodes()[n].level, reach).size);
            }
        }
        try {
            ensurePool(r, gradients, choice.bytes, largest);
        } catch (const GlOutOfMemory&) {
            if (!gradients) {
                throw;
            }
            gradientsRefused_ = true; // the next frame decides without them
            return updateWithin(r, st, budget);
        }
    }
    st = BrickFrameStats{};
    const std::vector<Shown> shown = showNodes(tree, choice, reach, gradients, r.uploadCap, st);
    lastShown_.clear();
    for (const Shown& sh : shown) {
        if (sh.level >= 0) {
            pool_->touch(sh.level, sh.id, frame_);
            lastShown_.emplace_back(sh.level, sh.id);
        }
    }
    upload(shown, r, st);
    makeTable(tree, shown, perLevel, r, st);
    st.levelsClassified = classified;
    st.planned = true;
    st.lodReason = choice.coarsened;
    if (st.pending > 0) {
        st.lodReason += (st.lodReason.empty() ? "" : "; ") + std::to_string(st.pending) +
                        " bricks still streaming in";
    }
    // Where everything shows at level 0 with nothing pending, the plan holds
    // for any camera that sees the same pages.
    if (st.pending == 0 && choice.coarsened.empty() && st.coarsestLevel == 0) {
        reusable_ = std::move(key);
    } else {
        reusable_.reset();
    }
    lastStats_ = st;
    return table_;
}

std::vector<Shown> BrickStreamer::showNodes(const BrickOctree& tree, const LevelChoice& choice,
                                            FilterReach reach, bool gradients,
                                            std::size_t uploadCap, BrickFrameStats& st) const {
    // What each node shows: its planned box if resident, else (beyond the
    // upload cap) a coarser one it holds, else the planned one uploaded.
    const auto& nodes = tree.nodes();
    const int levels = tree.levels();
    const std::size_t texelBytes = BrickPool::texelBytes(pool_->format(), gradients);
    std::vector<std::size_t> order = choice.shown;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return nodes[a].worth > nodes[b].worth; });
    std::vector<Shown> shown(nodes.size());
    std::size_t capped = 0;
    for (const std::size_t n : order) {
        const BrickOctree::Node& node = nodes[n];
        if (!node.box) {
            continue; // nothing to show at its level
        }
        ++st.bricksNeeded;
        const StoredBox want = storedBox(*node.box, node.level, reach);
        if (pool_->find(node.level, node.id, want)) {
            shown[n] = {node.level, node.id, want, false};
            continue;
        }
        const std::size_t cost = volumeOf(want.size) * texelBytes;
        // Over the cap (but one brick a frame, however large, so that every frame brings some).
        if (uploadCap > 0 && capped > 0 && capped + cost > uploadCap) {
            // An ancestor already resident stands in (its pages all lie in it).
            bool stood = false;
            for (int l = node.level + 1; l < levels && !stood; ++l) {
                const auto up = tree.ancestor(node, l);
                if (!up || !nodes[*up].box) {
                    continue;
                }
                const BrickOctree::Node& coarse = nodes[*up];
                const StoredBox held = storedBox(*coarse.box, l, reach);
                if (pool_->find(l, coarse.id, held)) {
                    shown[*up] = {l, coarse.id, held, false};
                    stood = true;
                }
            }
            if (!stood && node.level < levels - 1) { // nothing resident yet: the coarsest first
                const auto top = tree.ancestor(node, levels - 1);
                if (top && nodes[*top].box) {
                    const BrickOctree::Node& root = nodes[*top];
                    const StoredBox held = storedBox(*root.box, root.level, reach);
                    if (shown[*top].level < 0) {
                        shown[*top] = {root.level, root.id, held,
                                       !pool_->find(root.level, root.id, held)};
                    }
                    stood = true;
                }
            }
            if (stood) {
                ++st.pending;
                continue;
            }
        }
        capped += cost;
        shown[n] = {node.level, node.id, want, true};
    }
    return shown;
}

void BrickStreamer::upload(const std::vector<Shown>& shown, const BrickRequest& r,
                           BrickFrameStats& st) {
    // Room for the uploads; where the atlas has none, a new one takes the
    // frame's bricks over (GPU copies) and places them largest first.
    const Placements placed = placeUploads(pool_, shown, budget_, frame_);
    // A level at a time: each level has its own source.
    int levels = 0;
    for (const Shown& sh : shown) {
        levels = std::max(levels, sh.level + 1);
    }
    for (int l = 0; l < levels; ++l) {
        std::vector<BrickPool::Upload> uploads;
        for (const auto& [n, at] : placed) {
            if (shown[n].level == l) {
                uploads.push_back({l, shown[n].id, shown[n].stored, at});
            }
        }
        if (!uploads.empty()) {
            st.bytesUploaded += pool_->upload(uploads, source(l, r.cubic),
                                              r.cubic ? BrickEdge::Mirror : BrickEdge::Clamp,
                                              r.gradientUnit, frame_);
            st.bricksUploaded += uploads.size();
        }
    }
}

void BrickStreamer::makeTable(const BrickOctree& tree, const std::vector<Shown>& shown,
                              const std::vector<LevelBoxList>& perLevel, const BrickRequest& r,
                              BrickFrameStats& st) {
    // Each page drawn from the shown node that holds it, with its own box at that node's level.
    std::vector<ShownBrick> table(boxes_->brickCount());
    for (std::uint32_t b = 0; b < boxes_->brickCount(); ++b) {
        for (int l = 0; tree.hasPage(b) && l < tree.levels(); ++l) {
            const Shown& sh = shown[tree.nodeOf(b, l)];
            if (sh.level < 0) {
                continue;
            }
            if (const auto& box = perLevel[std::size_t(l)][b]) {
                table[b] = {pool_->find(sh.level, sh.id, sh.stored), *box};
            }
            break;
        }
    }
    std::vector<CellRanges> ranges;
    for (int l = 0; l < tree.levels(); ++l) {
        ranges.push_back({&grid(kCellSize, r.cubic, l), &levelCells(r.cubic, l)});
    }
    table_ = makeBrickTable(*boxes_, table, ranges, r.visible, r.decides, r.cubic);
    ++tableGeneration_;
    st.levelOfBrick.assign(table.size(), -1);
    for (std::size_t b = 0; b < table.size(); ++b) {
        st.levelOfBrick[b] = table[b].entry ? std::int8_t(table[b].entry->level) : std::int8_t(-1);
    }
    st.brickSize = boxes_->brickSize();
    // The bricks of the asked size that show something (the pages are finer).
    const glm::ivec3 userPer = (volume_.dims() + r.brickSize - 1) / r.brickSize;
    st.bricksTotal = std::size_t(userPer.x) * std::size_t(userPer.y) * std::size_t(userPer.z);
    std::vector<char> used(st.bricksTotal, 0);
    for (const ShownBrick& page : table) {
        if (!page.entry || !page.box.contributes) {
            continue;
        }
        const glm::ivec3 lo = page.box.lo / r.brickSize, hi = (page.box.hi - 1) / r.brickSize;
        for (int z = lo.z; z <= hi.z; ++z) {
            for (int y = lo.y; y <= hi.y; ++y) {
                for (int x = lo.x; x <= hi.x; ++x) {
                    used[std::size_t(x) + std::size_t(userPer.x) *
                                              (std::size_t(y) + std::size_t(userPer.y) * z)] = 1;
                }
            }
        }
    }
    st.bricksUsed = std::size_t(std::count(used.begin(), used.end(), 1));
    countResident(st);
}

void BrickStreamer::countResident(BrickFrameStats& st) const {
    const TexelFormat f = pool_->format();
    for (const auto& [key, e] : pool_->entries()) {
        const std::size_t texels = volumeOf(e.box.size);
        st.valueBytes += texels * f.gpuBytes;
        st.gradientBytes += texels * (BrickPool::texelBytes(f, pool_->hasGradients()) - f.gpuBytes);
    }
    st.tableBytes = table_.bytes();
    st.poolBytes = pool_->bytes();
    st.perLevel = table_.perLevel;
    st.bricksShown = 0;
    const int levels = int(st.perLevel.size());
    st.finestLevel = levels;
    st.coarsestLevel = 0;
    for (int l = 0; l < levels; ++l) {
        if (st.perLevel[std::size_t(l)] > 0) {
            st.bricksShown += st.perLevel[std::size_t(l)];
            st.finestLevel = std::min(st.finestLevel, l);
            st.coarsestLevel = l;
        }
    }
    st.finestLevel = std::min(st.finestLevel, st.coarsestLevel);
    st.gradientsCached = pool_->hasGradients();
}

} // namespace lucent
