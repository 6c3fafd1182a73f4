#include "render/BrickStreamer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/raycast/BSplinePrefilter.h"
#include "render/GlError.h"

namespace lucent {

namespace {

constexpr int kCellSize = 8;    // the leaping cells (as on the CPU)
constexpr int kGridOverlap = 3; // cell ranges cover every filter's reach at their level
// The boxes did not pack into an atlas within the budget.
struct PackingError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::size_t volumeOf(glm::ivec3 s) {
    return std::size_t(s.x) * std::size_t(s.y) * std::size_t(s.z);
}

// Packing order: the longest side first, then the volume.
bool largerBox(glm::ivec3 a, glm::ivec3 b) {
    const int ma = std::max({a.x, a.y, a.z}), mb = std::max({b.x, b.y, b.z});
    return ma > mb || (ma == mb && volumeOf(a) > volumeOf(b));
}

// A node of the octree: a brick of its level, covering 2^level pages a side.
struct Node {
    int level = 0;
    std::uint32_t id = 0;         // in its level's grid of nodes
    std::optional<SampleBox> box; // the union of its pages' boxes at its level
    double worth = 0.0;
};

struct Shown {
    int level = -1; // -1: not shown
    std::uint32_t id = 0;
    StoredBox stored;
    bool upload = false;
};

using Placements = std::vector<std::pair<std::size_t, glm::ivec3>>; // shown index, atlas origin

// A new atlas for the frame's boxes, at least half as large again as the
// old one (within the budget), packed largest first: resident boxes copied
// over on the GPU, the others placed for upload.
Placements repack(std::unique_ptr<BrickPool>& pool, const std::vector<Shown>& shown,
                  std::size_t budget, std::uint64_t frame) {
    const std::size_t texelBytes = BrickPool::texelBytes(pool->format(), pool->hasGradients());
    // Per shown brick: the box it takes (a resident one may be larger than planned).
    std::vector<std::size_t> items;
    std::vector<glm::ivec3> sizes(shown.size(), glm::ivec3(0));
    std::vector<const BrickPool::Entry*> resident(shown.size(), nullptr);
    std::size_t need = 0;
    glm::ivec3 largest(1);
    for (std::size_t n = 0; n < shown.size(); ++n) {
        if (shown[n].level < 0) {
            continue;
        }
        if (!shown[n].upload) {
            resident[n] = pool->find(shown[n].level, shown[n].id, shown[n].stored);
        }
        sizes[n] = resident[n] ? resident[n]->box.size : shown[n].stored.size;
        items.push_back(n);
        need += volumeOf(sizes[n]);
        largest = glm::max(largest, sizes[n]);
    }
    std::stable_sort(items.begin(), items.end(),
                     [&](std::size_t a, std::size_t b) { return largerBox(sizes[a], sizes[b]); });
    GLint maxSide = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSide);
    const std::size_t cap = budget / texelBytes;
    // A pool that held bricks before grows by half, so that it is not
    // repacked again at the next transfer function; a new one by what it needs.
    const bool grown = pool->residentCount() > 0;
    std::size_t target =
        std::min(std::max(need + need / 8, grown ? volumeOf(pool->extent()) * 3 / 2 : 0), cap);
    for (;;) {
        const glm::ivec3 extent =
            BoxAtlas::extentFor(std::max(target, need), largest, int(maxSide), cap);
        BoxAtlas trial(extent);
        std::vector<glm::ivec3> at;
        for (const std::size_t n : items) {
            const auto o = trial.place(sizes[n]);
            if (!o) {
                break;
            }
            at.push_back(*o);
        }
        if (at.size() < items.size()) {
            if (target >= cap) {
                throw PackingError("the frame's " + std::to_string(items.size()) +
                                   " bricks do not pack into the budget of " +
                                   std::to_string(budget >> 20) + " MiB");
            }
            target = std::min(cap, target + target / 8 + 1);
            continue;
        }
        auto fresh = std::make_unique<BrickPool>(pool->format(), pool->hasGradients(), extent);
        Placements uploads;
        for (std::size_t m = 0; m < items.size(); ++m) {
            const std::size_t n = items[m];
            // The same boxes in the same order land where the trial put them.
            const glm::ivec3 o = fresh->place({glm::ivec3(0), sizes[n]}, frame).value_or(at[m]);
            if (resident[n]) {
                fresh->copyFrom(*pool, *resident[n], o, frame);
            } else {
                uploads.emplace_back(n, o);
            }
        }
        checkGl("moving the resident bricks into a new atlas");
        pool = std::move(fresh);
        return uploads;
    }
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
            if (packing_ < 0.35) {
                throw BudgetError(e.what());
            }
            packing_ -= 0.1;
        }
    }
}

const BrickTable& BrickStreamer::updateWithin(const BrickRequest& r, BrickFrameStats& st,
                                              std::size_t budget) {
    ++frame_;
    const int pageSize = std::min(r.brickSize, kPageSize);
    if (!boxes_ || boxes_->brickSize() != pageSize) {
        boxes_ = std::make_unique<BrickBoxes>(volume_.dims(), pageSize, kCellSize);
    }
    const TexelFormat f = format(r.cubic, r.halfFloat);

    // Each brick's box per level, level 0 first; coarser levels only when needed.
    std::vector<std::vector<std::optional<SampleBox>>> perLevel;
    std::vector<std::vector<std::uint8_t>> cellsPerLevel;
    const auto addLevel = [&](int level) {
        // Level 0's trilinear samples in a cell read only its voxels and the
        // next (an overlap of 1 decides what they can show); a coarser
        // level's cells answer for level-0 cells through their overlap of 3.
        const int overlap = level == 0 && !r.cubic ? 1 : kGridOverlap;
        cellsPerLevel.push_back(boxes_->visibleCells(grid(kCellSize, r.cubic, level, overlap),
                                                     level, r.visible, r.clip));
        perLevel.push_back(boxes_->boxes(cellsPerLevel.back(), r.withNeighbours));
        for (std::size_t b = 0; b < perLevel.back().size(); ++b) {
            auto& box = perLevel.back()[b];
            if (box && r.inView && !r.inView(glm::dvec3(box->lo), glm::dvec3(box->hi - 1))) {
                box.reset();
            }
            if (box && !r.tight) { // the whole page, as bricks were before boxes
                box->lo = boxes_->brickIndex(b) * boxes_->brickSize();
                box->hi = glm::min(box->lo + boxes_->brickSize(), volume_.dims());
            }
        }
    };
    const FilterReach computed = filterReach(r.cubic, r.shaded);
    const FilterReach cached = filterReach(r.cubic, false);
    const auto bytesAt = [&](int level, FilterReach reach, std::size_t texelBytes) {
        std::size_t sum = 0;
        for (const auto& box : perLevel[std::size_t(level)]) {
            sum += box ? volumeOf(storedBox(*box, level, reach).size) * texelBytes : 0;
        }
        return sum;
    };
    addLevel(0);
    const bool mayCache = r.shaded && r.gradientCache && !r.cubic && !gradientsRefused_;
    const std::size_t valuesOnly = BrickPool::texelBytes(f, false);
    // Coarser levels where level 0 does not fit, or to stand in while bricks stream.
    if (bytesAt(0, computed, valuesOnly) > budget || r.uploadCap > 0) {
        for (int level = 1; level < levelCount(); ++level) {
            addLevel(level);
        }
    }
    const int levels = int(perLevel.size());

    // The octree: per level, nodes of 2^level pages a side with the union of
    // their pages' boxes; what refining each is worth (its pages' most).
    const glm::ivec3 pages = boxes_->bricksPerAxis();
    const auto pageIndex = [&](std::uint32_t b) { return boxes_->brickIndex(b); };
    std::vector<double> pageWorth(boxes_->brickCount(), 0.0);
    std::vector<char> anyBox(boxes_->brickCount(), 0);
    const int cellsPerPage = std::max(1, pageSize / kCellSize);
    const glm::ivec3 cp = boxes_->cellsPerAxis();
    const BrickGrid& cells0 = grid(kCellSize, r.cubic, 0);
    for (std::uint32_t b = 0; b < boxes_->brickCount(); ++b) {
        for (int l = 0; l < levels; ++l) {
            anyBox[b] = anyBox[b] || perLevel[std::size_t(l)][b].has_value();
        }
        if (!anyBox[b]) {
            continue;
        }
        const glm::ivec3 lo = pageIndex(b) * pageSize;
        const glm::ivec3 hi = glm::min(lo + pageSize, volume_.dims());
        // What it shows: its visible cells at level 0, and above all those
        // where a surface passes (values on both sides of what the transfer
        // function shows): there coarser voxels blur what is drawn.
        double shows = 0.0;
        for (int z = lo.z / kCellSize; z * kCellSize < hi.z; ++z) {
            for (int y = lo.y / kCellSize; y * kCellSize < hi.y; ++y) {
                for (int x = lo.x / kCellSize; x * kCellSize < hi.x; ++x) {
                    const std::size_t c =
                        std::size_t(x) +
                        std::size_t(cp.x) * (std::size_t(y) + std::size_t(cp.y) * z);
                    if (cellsPerLevel[0][c] == 0) {
                        continue;
                    }
                    const Brick& range = cells0.bricks()[c];
                    const bool surface = !r.visible(range.minValue, range.minValue) ||
                                         !r.visible(range.maxValue, range.maxValue);
                    shows += surface ? 1.0 : 0.25;
                }
            }
        }
        const double content =
            std::sqrt((shows + 0.1) / (std::pow(double(cellsPerPage), 3.0) + 0.1));
        pageWorth[b] = r.worth ? r.worth(glm::dvec3(lo), glm::dvec3(hi - 1), content) : content;
    }
    std::vector<Node> nodes;
    auto nodeAt =
        std::vector<std::map<std::uint32_t, std::size_t>>(std::size_t(levels)); // id -> node
    std::vector<glm::ivec3> nodesPer(std::size_t(levels), glm::ivec3(0));
    for (int l = 0; l < levels; ++l) {
        nodesPer[std::size_t(l)] = (pages + (1 << l) - 1) / (1 << l);
        const glm::ivec3 np = nodesPer[std::size_t(l)];
        for (std::uint32_t b = 0; b < boxes_->brickCount(); ++b) {
            if (!anyBox[b]) {
                continue;
            }
            const glm::ivec3 at = pageIndex(b) >> l;
            const auto id = std::uint32_t(at.x + np.x * (at.y + np.y * at.z));
            auto [it, added] = nodeAt[std::size_t(l)].try_emplace(id, nodes.size());
            if (added) {
                nodes.push_back(Node{l, id, std::nullopt, 0.0});
            }
            Node& node = nodes[it->second];
            node.worth = std::max(node.worth, pageWorth[b]);
            if (const auto& box = perLevel[std::size_t(l)][b]) {
                if (!node.box) {
                    node.box = box;
                } else {
                    node.box->lo = glm::min(node.box->lo, box->lo);
                    node.box->hi = glm::max(node.box->hi, box->hi);
                    node.box->contributes = node.box->contributes || box->contributes;
                }
            }
        }
    }
    const auto nodeOf = [&](std::uint32_t page, int level) {
        const glm::ivec3 at = pageIndex(page) >> level;
        const glm::ivec3 np = nodesPer[std::size_t(level)];
        return nodeAt[std::size_t(level)].at(std::uint32_t(at.x + np.x * (at.y + np.y * at.z)));
    };
    const auto choose = [&](FilterReach reach, std::size_t texelBytes, std::size_t within) {
        std::vector<LodNode> tree(nodes.size());
        std::vector<std::size_t> roots;
        for (std::size_t n = 0; n < nodes.size(); ++n) {
            const Node& node = nodes[n];
            tree[n].level = node.level;
            tree[n].worth = node.worth;
            tree[n].bytes =
                node.box ? volumeOf(storedBox(*node.box, node.level, reach).size) * texelBytes : 0;
            if (node.level == levels - 1) {
                roots.push_back(n);
            }
        }
        for (std::uint32_t b = 0; b < boxes_->brickCount(); ++b) {
            for (int l = 1; anyBox[b] && l < levels; ++l) {
                auto& children = tree[nodeOf(b, l)].children;
                const std::size_t child = nodeOf(b, l - 1);
                if (std::find(children.begin(), children.end(), child) == children.end()) {
                    children.push_back(child);
                }
            }
        }
        return chooseLevels(tree, roots, within, r.policy);
    };
    LevelChoice choice = choose(computed, valuesOnly, budget);
    // Gradients are cached when they cost no brick a finer level.
    bool gradients = false;
    if (mayCache || (pool_ && pool_->hasGradients() && !r.cubic)) {
        try {
            const LevelChoice with = choose(cached, BrickPool::texelBytes(f, true), budget);
            if (with.shown == choice.shown) {
                choice = with;
                gradients = true;
            }
        } catch (const BudgetError&) {
            // not even the levels tried hold them: computed gradients
        }
    }
    const FilterReach reach = gradients ? cached : computed;
    glm::ivec3 largest(1);
    for (const std::size_t n : choice.shown) {
        if (const auto& box = nodes[n].box) {
            largest = glm::max(largest, storedBox(*box, nodes[n].level, reach).size);
        }
    }
    if (!pool_ || poolKind_ != std::tuple(r.brickSize, r.cubic, gradients)) {
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

    // What each node shows: its planned box if resident, else (beyond the
    // upload cap) a coarser one it holds, else the planned one uploaded.
    std::vector<std::size_t> order = choice.shown;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return nodes[a].worth > nodes[b].worth; });
    std::vector<Shown> shown(nodes.size());
    std::size_t capped = 0;
    st = BrickFrameStats{};
    for (const std::size_t n : order) {
        const Node& node = nodes[n];
        if (!node.box) {
            continue; // nothing to show at its level
        }
        ++st.bricksNeeded;
        const StoredBox want = storedBox(*node.box, node.level, reach);
        if (pool_->find(node.level, node.id, want)) {
            shown[n] = {node.level, node.id, want, false};
            continue;
        }
        const std::size_t cost = volumeOf(want.size) * BrickPool::texelBytes(f, gradients);
        // Over the cap (but one brick a frame, however large, so that every frame brings some).
        if (r.uploadCap > 0 && capped > 0 && capped + cost > r.uploadCap) {
            // An ancestor already resident stands in (its pages all lie in it).
            const glm::ivec3 np = nodesPer[std::size_t(node.level)];
            const glm::ivec3 at(int(node.id % std::uint32_t(np.x)),
                                int((node.id / std::uint32_t(np.x)) % std::uint32_t(np.y)),
                                int(node.id / std::uint32_t(np.x * np.y)));
            bool stood = false;
            for (int l = node.level + 1; l < levels && !stood; ++l) {
                const glm::ivec3 up = at >> (l - node.level);
                const glm::ivec3 upPer = nodesPer[std::size_t(l)];
                const auto it = nodeAt[std::size_t(l)].find(
                    std::uint32_t(up.x + upPer.x * (up.y + upPer.y * up.z)));
                if (it == nodeAt[std::size_t(l)].end() || !nodes[it->second].box) {
                    continue;
                }
                const Node& coarse = nodes[it->second];
                const StoredBox held = storedBox(*coarse.box, l, reach);
                if (pool_->find(l, coarse.id, held)) {
                    shown[it->second] = {l, coarse.id, held, false};
                    stood = true;
                }
            }
            if (!stood) { // nothing resident yet: the coarsest level first
                const glm::ivec3 top = at >> (levels - 1 - node.level);
                const glm::ivec3 topPer = nodesPer[std::size_t(levels - 1)];
                const auto it = nodeAt[std::size_t(levels - 1)].find(
                    std::uint32_t(top.x + topPer.x * (top.y + topPer.y * top.z)));
                if (node.level < levels - 1 && it != nodeAt[std::size_t(levels - 1)].end() &&
                    nodes[it->second].box) {
                    const Node& root = nodes[it->second];
                    const StoredBox held = storedBox(*root.box, root.level, reach);
                    if (shown[it->second].level < 0) {
                        shown[it->second] = {root.level, root.id, held,
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
    for (const Shown& sh : shown) {
        if (sh.level >= 0) {
            pool_->touch(sh.level, sh.id, frame_);
        }
    }

    // Room for the uploads; where the atlas has none, a new one takes the
    // frame's bricks over (GPU copies) and places them largest first.
    Placements placed;
    std::vector<std::size_t> toPlace;
    for (std::size_t n = 0; n < shown.size(); ++n) {
        if (shown[n].upload) {
            toPlace.push_back(n);
        }
    }
    std::stable_sort(toPlace.begin(), toPlace.end(), [&](std::size_t a, std::size_t b) {
        return largerBox(shown[a].stored.size, shown[b].stored.size);
    });
    bool fits = true;
    for (std::size_t m = 0; m < toPlace.size() && fits; ++m) {
        const auto at = pool_->place(shown[toPlace[m]].stored, frame_);
        fits = at.has_value();
        if (fits) {
            placed.emplace_back(toPlace[m], *at);
        }
    }
    if (!fits) {
        placed = repack(pool_, shown, budget_, frame_);
    }
    // Uploads, a level at a time (each level has its own source).
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

    // The table the shader reads: each page drawn from the shown node that
    // holds it, with its own box at that node's level.
    std::vector<ShownBrick> table(boxes_->brickCount());
    for (std::uint32_t b = 0; b < boxes_->brickCount(); ++b) {
        for (int l = 0; anyBox[b] && l < levels; ++l) {
            const Shown& sh = shown[nodeOf(b, l)];
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
    for (int l = 0; l < levels; ++l) {
        ranges.push_back({&grid(kCellSize, r.cubic, l), &levelCells(r.cubic, l)});
    }
    table_ = makeBrickTable(*boxes_, table, ranges, r.visible, r.decides, r.cubic);
    st.levelOfBrick.assign(table.size(), -1);
    for (std::size_t b = 0; b < table.size(); ++b) {
        st.levelOfBrick[b] = table[b].entry ? std::int8_t(table[b].entry->level) : std::int8_t(-1);
    }
    st.brickSize = pageSize;
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

    for (const auto& [key, e] : pool_->entries()) {
        const std::size_t texels = volumeOf(e.box.size);
        st.valueBytes += texels * f.gpuBytes;
        st.gradientBytes += texels * (BrickPool::texelBytes(f, pool_->hasGradients()) - f.gpuBytes);
    }
    st.tableBytes = table_.bytes();
    st.poolBytes = pool_->bytes();
    st.perLevel = table_.perLevel;
    st.bricksShown = 0;
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
    st.lodReason = choice.coarsened;
    if (st.pending > 0) {
        st.lodReason += (st.lodReason.empty() ? "" : "; ") + std::to_string(st.pending) +
                        " bricks still streaming in";
    }
    return table_;
}

} // namespace lucent
