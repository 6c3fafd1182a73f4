#pragma once
// The overlay of a fused render (RenderOverlay, core/scene/RenderDescription.h) on the
// GPU: its volume as one R32F 3D texture on the base's grid (trilinear, the base's level-0
// index space), and its table (core/raycast/OverlaySampler.h: row 0 the colour and the
// opacity corrected for the step, row 1 the raw opacity). The volume is uploaded when the
// overlay's fingerprint (OverlaySampler.h: address, grid, a hash of its values) changed, the
// table when the map, the opacity or the step changed. Outside the brick pool's budget: the whole
// overlay, at full resolution. Private to render/.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <tuple>

#include "core/scene/RenderDescription.h"
#include "render/GlObjects_p.h"

namespace lucent {

class OverlayTextures {
public:
    // Uploads what changed; returns the bytes uploaded this frame. Throws GlError.
    std::size_t update(const RenderOverlay& overlay, double stepRatio);
    // Fused DVR's leaping (as the CPU's, core/raycast/OverlayLeaping.h): per leaping cell
    // (cellSize voxels, cellsPerAxis) and per page (brickSize, bricksPerAxis), 1 where the
    // overlay shows nothing under the window: every voxel a sample there can read (2 voxels
    // of overlap, NaN ignored) lies below the window's first visible entry. Rebuilt when
    // the overlay, the window or the layout changed. Throws GlError.
    void updateLeaping(const RenderOverlay& overlay, int cellSize, glm::ivec3 cellsPerAxis,
                       int brickSize, glm::ivec3 bricksPerAxis);
    GLuint emptyCells() const { return emptyCells_.get(); }
    GLuint emptyBricks() const { return emptyBricks_.get(); }

    // Sets the shader's overlay uniforms (uOverlayLow, uOverlayWidth, uOverlayInvDims).
    void setUniforms(const ShaderProgram& program, const RenderOverlay& overlay) const;

    GLuint volume() const { return volume_.get(); }
    GLuint table() const { return table_.get(); }
    std::size_t bytes() const { return bytes_; } // GPU memory of the volume texture

private:
    GlTexture volume_, table_, emptyCells_, emptyBricks_;
    std::uint64_t fingerprint_ = 0;
    glm::ivec3 dims_{0};
    std::size_t bytes_ = 0;
    std::optional<std::tuple<FusionColourMap, double, double>> tableKey_; // map, opacity, step
    // fingerprint, window, cell size, brick size
    std::optional<std::tuple<std::uint64_t, double, double, int, int>> leapingKey_;
};

} // namespace lucent
