#pragma once
// Distance maps that let a ray leap several empty places at once (Deakin &
// Knackstedt 2019, distance maps for empty space skipping): per leaping cell,
// its code (SceneTextures has them alone) | r << 2, r the reach of the cube of
// cells within r of it that are all leapt (core/raycast/LeapReach.h), so that
// a cell takes one fetch; per
// block of 2 x 2 x 2 voxels (core/volume/BlockRanges.h), 0 where a sample in
// it may show, else 1 + the reach of the cube of blocks around it where none
// does. Each is rebuilt only when what it depends on changed. Private to render/.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "core/scene/RenderDescription.h"
#include "core/volume/BlockRanges.h"
#include "render/BrickTable.h"
#include "render/GlObjects_p.h"

namespace lucent {

// The maps a cast reads (the switches leap-distance and block-skipping where
// they apply), and the shader's #defines for them.
struct LeapMaps {
    bool cellReach = false, blockSkip = false;
    std::string defines() const;
};

// The cells' map as the shader reads it: per cell its code (0, 1 or 2, as
// BrickTable::codes) | r << 2, r = min(leapReach, 63), a smaller cube inside
// the leapt one where the reach is longer.
std::vector<std::uint8_t> cellCodesAndReach(const std::vector<std::uint8_t>& codes,
                                            glm::ivec3 cellsPerAxis);

class LeapTextures {
public:
    LeapTextures();
    ~LeapTextures();
    LeapTextures(const LeapTextures&) = delete;
    LeapTextures& operator=(const LeapTextures&) = delete;

    // Which maps `d` reads, brought up to date: the cells' with leaping
    // (not with an overlay); the blocks' for DVR, post-classified, trilinear or
    // nearest, not pre-integrated, no overlay, bricks of whole cells, a volume
    // blocksFor() takes. visible: the values a sample may show (visibleValueRange),
    // widened here by a table cell and the float rounding of a sample over the
    // table's range [tableLo, tableHi].
    struct Visible {
        double lo, hi, tableCell, tableLo, tableHi;
    };
    // Returns the shader's #defines for them.
    // `generation` (BrickStreamer::tableGeneration) names the table: a frame
    // with the last one's compares nothing.
    std::string update(const RenderDescription& d, const Volume& volume, const BrickTable& table,
                       std::uint64_t generation, int cellSize, const Visible& visible);
    // GPU memory of the maps the last update() reads (one byte a cell or block).
    std::size_t bytes() const {
        return (maps_.cellReach ? cellBytes_ : 0) + (maps_.blockSkip ? blockBytes_ : 0);
    }
    // The last update()'s maps on units `unit` and `unit` + 1, and their uniforms.
    void bind(const ShaderProgram& p, GLuint unit) const;

    // Whether the blocks' map is made for a volume: their ranges take a byte
    // of CPU memory per voxel, so up to 2^28 voxels (512 x 512 x 1024).
    static bool blocksFor(const Volume& volume) {
        return volume.geometry().voxelCount() <= (std::size_t(1) << 28);
    }

private:
    // The cells' reach over the cells the table leaps (code != 0).
    void updateCells(const BrickTable& table, std::uint64_t generation);
    // The blocks' map: a sample in a block shows nothing where its leaping
    // cell (of cellSize voxels) is leapt, or where its brick is drawn from
    // level 0 and every value the block gives lies below lo or above hi.
    // table.brickSize is a multiple of cellSize, cellSize a multiple of 2.
    void updateBlocks(const Volume& volume, const BrickTable& table, std::uint64_t generation,
                      int cellSize, float lo, float hi);

    GlTexture cellReach_, blockReach_;
    std::size_t cellBytes_ = 0, blockBytes_ = 0;
    LeapMaps maps_; // the last update()'s
    std::optional<std::vector<std::uint8_t>> cellKey_;
    std::uint64_t cellGeneration_ = 0, blockGeneration_ = 0; // of the tables the keys hold
    std::unique_ptr<BlockRanges> ranges_;                    // of the volume, made once
    const Volume* rangesOf_ = nullptr;
    std::optional<std::tuple<std::vector<std::uint8_t>, std::vector<glm::ivec4>, int, float, float>>
        blockKey_;
};

} // namespace lucent
