#include "render/LeapTextures.h"

#include <algorithm>
#include <cmath>

#include "core/raycast/LeapReach.h"

namespace lucent {

namespace {

constexpr int kBlockReach = 6; // blocks: the cells' distance map leaps further

} // namespace

std::vector<std::uint8_t> cellCodesAndReach(const std::vector<std::uint8_t>& codes,
                                            glm::ivec3 cellsPerAxis) {
    std::vector<std::uint8_t> bits = leapReach(codes, cellsPerAxis);
    for (std::size_t i = 0; i < bits.size(); ++i) {
        bits[i] = std::uint8_t((codes[i] & 3) | std::min<int>(bits[i], 63) << 2);
    }
    return bits;
}

std::string LeapMaps::defines() const {
    const auto flag = [](bool b) { return b ? std::string("true") : std::string("false"); };
    return "#define LUCENT_CELL_REACH " + flag(cellReach) + "\n#define LUCENT_BLOCK_SKIP " +
           flag(blockSkip) + "\n";
}

LeapTextures::LeapTextures() = default;
LeapTextures::~LeapTextures() = default;

std::string LeapTextures::update(const RenderDescription& d, const Volume& volume,
                                 const BrickTable& table, std::uint64_t generation, int cellSize,
                                 const Visible& visible) {
    const SamplingSettings& s = d.sampling;
    const bool leap = s.emptySpaceLeaping && d.overlay.volume == nullptr;
    LeapMaps& maps = maps_;
    maps.cellReach = leap && s.leapDistance;
    maps.blockSkip = leap && s.blockSkipping && d.mode == RenderMode::Dvr && !s.preintegrate &&
                     s.interpolation != Interpolation::Cubic &&
                     s.classification == Classification::Post && table.brickSize % cellSize == 0 &&
                     blocksFor(volume);
    if (maps.cellReach) {
        updateCells(table, generation);
    }
    if (maps.blockSkip) { // as the CPU's invisible cells: a table cell and float ulps
        const double margin = visible.tableCell +
                              4e-6 * std::max(std::abs(visible.tableLo), std::abs(visible.tableHi));
        updateBlocks(volume, table, generation, cellSize,
                     float(std::max(visible.lo - margin, -3.0e38)),
                     float(std::min(visible.hi + margin, 3.0e38)));
    }
    return maps.defines();
}

void LeapTextures::bind(const ShaderProgram& p, GLuint unit) const {
    glBindTextureUnit(unit, maps_.cellReach ? cellReach_.get() : 0);
    p.set("uCellReach", int(unit));
    glBindTextureUnit(unit + 1, maps_.blockSkip ? blockReach_.get() : 0);
    p.set("uBlockReach", int(unit + 1));
    p.set("uBlocksPerAxis", ranges_ ? ranges_->blocksPerAxis() : glm::ivec3(0));
}

void LeapTextures::updateCells(const BrickTable& table, std::uint64_t generation) {
    if (cellKey_ && (generation == cellGeneration_ || *cellKey_ == table.codes)) {
        cellGeneration_ = generation;
        return;
    }
    // The code beside the reach, so that a cell takes one fetch.
    const std::vector<std::uint8_t> reach = cellCodesAndReach(table.codes, table.cellsPerAxis);
    cellReach_ =
        makeTexture3D(GL_R8UI, table.cellsPerAxis, GL_RED_INTEGER, GL_UNSIGNED_BYTE, reach.data());
    cellBytes_ = reach.size();
    checkGl("leaping cells' reach");
    cellKey_ = table.codes;
    cellGeneration_ = generation;
}

void LeapTextures::updateBlocks(const Volume& volume, const BrickTable& table,
                                std::uint64_t generation, int cellSize, float lo, float hi) {
    if (!ranges_ || rangesOf_ != &volume) {
        ranges_ = std::make_unique<BlockRanges>(volume);
        rangesOf_ = &volume;
        blockKey_.reset();
    }
    if (blockKey_ && generation == blockGeneration_ && std::get<2>(*blockKey_) == cellSize &&
        std::get<3>(*blockKey_) == lo && std::get<4>(*blockKey_) == hi) {
        return; // the same table: nothing to copy or compare
    }
    auto key = std::tuple(table.codes, table.page, cellSize, lo, hi);
    blockGeneration_ = generation;
    if (blockKey_ == key) {
        return;
    }
    const BlockRanges& r = *ranges_;
    const glm::ivec3 blocks = r.blocksPerAxis(), cells = table.cellsPerAxis,
                     bricks = table.bricksPerAxis;
    const int size = BlockRanges::kBlockSize;
    std::vector<int> cellOfX(std::size_t(blocks.x)), brickOfX(std::size_t(blocks.x));
    for (int x = 0; x < blocks.x; ++x) {
        cellOfX[std::size_t(x)] = x * size / cellSize;
        brickOfX[std::size_t(x)] = x * size / table.brickSize;
    }
    std::vector<std::uint8_t> leapable(r.count(), 0);
#pragma omp parallel for schedule(static)
    for (int z = 0; z < blocks.z; ++z) {
        for (int y = 0; y < blocks.y; ++y) {
            const glm::ivec2 c = glm::ivec2(y, z) * size / cellSize,
                             b = glm::ivec2(y, z) * size / table.brickSize;
            const std::uint8_t* cellRow =
                table.codes.data() +
                std::size_t(cells.x) * (std::size_t(c.x) + std::size_t(cells.y) * c.y);
            const glm::ivec4* brickRow =
                table.page.data() +
                std::size_t(bricks.x) * (std::size_t(b.x) + std::size_t(bricks.y) * b.y);
            const std::size_t row = r.idOf({0, y, z});
            for (int x = 0; x < blocks.x; ++x) {
                // Page w = state | level << 2: 1 is resident at level 0, whose
                // voxels the ranges are.
                const bool empty = cellRow[cellOfX[std::size_t(x)]] != 0 ||
                                   (brickRow[brickOfX[std::size_t(x)]].w == 1 &&
                                    r.outside(row + std::size_t(x), lo, hi));
                leapable[row + std::size_t(x)] = empty ? 1 : 0;
            }
        }
    }
    // A short reach: the cells' map takes the rays further.
    std::vector<std::uint8_t> reach = leapReachWithin(leapable, blocks, kBlockReach);
    for (std::size_t i = 0; i < reach.size(); ++i) {
        reach[i] = leapable[i] != 0 ? std::uint8_t(reach[i] + 1) : 0;
    }
    blockReach_ = makeTexture3D(GL_R8UI, blocks, GL_RED_INTEGER, GL_UNSIGNED_BYTE, reach.data());
    blockBytes_ = reach.size();
    checkGl("sample blocks' reach");
    blockKey_ = std::move(key);
}

} // namespace lucent
