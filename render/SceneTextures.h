#pragma once
// What the shader reads besides the brick pool: the page table of the level,
// the leaping cells' codes and ranges, and the transfer-function tables. Each
// is rebuilt only when what it depends on changed, so frames that only move
// the camera upload nothing. Private to render/.

#include <cstdint>
#include <functional>
#include <optional>
#include <tuple>
#include <vector>

#include "core/tf/TransferFunction.h"
#include "core/volume/BrickGrid.h"
#include "core/volume/BrickResidency.h"
#include "render/GlObjects_p.h"

namespace lucent {

class SceneTextures {
public:
    // Page entry per brick of `grid`: slot origin (in slots) and 1 resident,
    // 2 resident only for its neighbours, 0 absent. Cells: 2 leap the brick,
    // 1 leap the cell, 0 sample. `decides` (DVR, iso): codes from visibility;
    // otherwise (MIP, MinIP, average) only absent bricks are leapt.
    struct Bricks {
        const BrickGrid* grid = nullptr;
        const BrickGrid* cells = nullptr;
        const ResidencyPlan* plan = nullptr;
        std::vector<glm::ivec3> slotOrigins; // per brick of the plan
        std::function<bool(double, double)> visible;
        bool decides = true;
        bool cubic = false; // ranges of spline coefficients keep a margin
    };
    // `signature` says everything the textures depend on besides the plan and
    // slots (transfer function, mode, iso value, level).
    void updateBricks(const Bricks& b, const std::vector<double>& signature);

    // Row 0: alpha corrected for stepRatio; row 1: alpha per dt_ref. With
    // preintegrate, the pre-integration table too.
    void updateTables(const TransferFunction& tf, double lo, double hi, double stepRatio,
                      bool preintegrate, int tableSize, int preintegrationSize);

    GLuint pageTable() const { return pageTable_.get(); }
    GLuint cellCode() const { return cellCode_.get(); }
    GLuint cellRange() const { return cellRange_.get(); }
    GLuint table() const { return table_.get(); }
    GLuint preintegrationTable() const { return preTable_.get(); }
    glm::ivec3 cellsPerAxis() const { return cellsPerAxis_; }

private:
    GlTexture pageTable_, cellCode_, cellRange_, table_, preTable_, spareTable_;
    glm::ivec3 cellsPerAxis_{0};
    std::optional<std::tuple<std::vector<double>, std::vector<std::uint32_t>,
                             std::vector<std::uint8_t>, std::vector<glm::ivec3>>>
        bricksKey_;
    // The pre-integration table in use and the one before it (another step).
    std::optional<std::tuple<TransferFunction, double, double, double>> tableKey_, preKey_,
        spareKey_;
};

} // namespace lucent
