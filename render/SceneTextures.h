#pragma once
// What the shader reads besides the brick pool: the page table of the bricks,
// the leaping cells' codes and ranges, and the transfer-function tables. Each
// is rebuilt only when what it depends on changed, so frames that only move
// the camera upload nothing. Private to render/.

#include <cstdint>
#include <functional>
#include <optional>
#include <tuple>
#include <vector>

#include "core/tf/TransferFunction.h"
#include "render/BrickTable.h"
#include "render/GlObjects_p.h"

namespace lucent {

class SceneTextures {
public:
    // The page table, the bricks' sample boxes and the leaping cells
    // (BrickTable.h), uploaded when they changed: never for the generation
    // (BrickStreamer::tableGeneration) last given. True when uploaded.
    bool updateBricks(const BrickTable& table, std::uint64_t generation);

    // Row 0: alpha corrected for stepRatio; row 1: alpha per dt_ref. With
    // preintegrate, the pre-integration table too.
    void updateTables(const TransferFunction& tf, double lo, double hi, double stepRatio,
                      bool preintegrate, int tableSize, int preintegrationSize);

    GLuint pageEntry() const { return pageEntry_.get(); } // BrickTable::entries

    GLuint cellCode() const { return cellCode_.get(); }
    GLuint cellRange() const { return cellRange_.get(); }
    GLuint table() const { return table_.get(); }
    GLuint preintegrationTable() const { return preTable_.get(); }
    glm::ivec3 cellsPerAxis() const { return cellsPerAxis_; }

private:
    GlTexture pageEntry_, cellCode_, cellRange_, table_, preTable_, spareTable_;
    glm::ivec3 cellsPerAxis_{0};
    std::optional<BrickTable> bricksKey_;
    std::uint64_t generation_ = 0;
    // The pre-integration table in use and the one before it (another step).
    std::optional<std::tuple<TransferFunction, double, double, double>> tableKey_, preKey_,
        spareKey_;
};

} // namespace lucent
