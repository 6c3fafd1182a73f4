#include "render/OverlayTextures.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/raycast/OverlaySampler.h"
#include "core/volume/BrickGrid.h"
#include "render/GlError.h"

namespace lucent {

std::size_t OverlayTextures::update(const RenderOverlay& overlay, double stepRatio) {
    std::size_t uploaded = 0;
    const Volume& v = *overlay.volume;
    const std::uint64_t fingerprint = overlayFingerprint(v);
    if (fingerprint_ != fingerprint || volume_.get() == 0) {
        volume_.reset();
        fingerprint_ = 0;
        const glm::ivec3 d = v.dims();
        GlTexture t = makeTexture(GL_TEXTURE_3D);
        glTextureParameteri(t.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(t.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        for (const GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) {
            glTextureParameteri(t.get(), wrap, GL_CLAMP_TO_EDGE);
        }
        glTextureStorage3D(t.get(), 1, GL_R32F, d.x, d.y, d.z);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTextureSubImage3D(t.get(), 0, 0, 0, 0, d.x, d.y, d.z, GL_RED, GL_FLOAT,
                            v.voxels<float>().data());
        checkGl("uploading the overlay volume");
        volume_ = std::move(t);
        fingerprint_ = fingerprint;
        dims_ = d;
        bytes_ = v.byteCount();
        uploaded += bytes_;
    }
    const auto key = std::tuple(overlay.style.colourMap, overlay.style.opacity, stepRatio);
    if (tableKey_ != key || table_.get() == 0) {
        const OverlayTable entries = overlayTable(overlay.style, stepRatio);
        std::vector<glm::vec4> rows(2 * entries.size());
        for (std::size_t i = 0; i < entries.size(); ++i) {
            rows[i] = glm::vec4(entries[i].colour, entries[i].alpha);
            rows[entries.size() + i] = glm::vec4(entries[i].colour, entries[i].rawAlpha);
        }
        table_ = makeTexture2D(GL_RGBA32F, int(entries.size()), 2);
        glTextureSubImage2D(table_.get(), 0, 0, 0, int(entries.size()), 2, GL_RGBA, GL_FLOAT,
                            rows.data());
        checkGl("the overlay's table");
        tableKey_ = key;
        uploaded += rows.size() * sizeof(glm::vec4);
    }
    return uploaded;
}

namespace {

// Per brick of a grid of `size` over the overlay: 1 where it shows nothing under the window.
std::vector<std::uint8_t> emptyFlags(const Volume& overlay, const FusionStyle& style, int size,
                                     glm::ivec3 perAxis) {
    const BrickGrid grid(overlay, size, 2);
    if (grid.bricksPerAxis() != perAxis) {
        throw std::logic_error("overlay leaping: the overlay's cells are not the base's");
    }
    const double low = style.center - 0.5 * style.width;
    const double first = low + 0.5 * style.width / 255.0;
    const double margin = 1e-5 * (std::abs(low) + std::abs(style.width) + 1.0);
    std::vector<std::uint8_t> flags(grid.count());
    for (std::size_t i = 0; i < grid.count(); ++i) {
        flags[i] = double(grid.bricks()[i].maxValue) < first - margin ? 1 : 0;
    }
    return flags;
}

GlTexture flagTexture(const std::vector<std::uint8_t>& flags, glm::ivec3 size) {
    GlTexture t = makeTexture(GL_TEXTURE_3D);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureStorage3D(t.get(), 1, GL_R8UI, size.x, size.y, size.z);
    glTextureSubImage3D(t.get(), 0, 0, 0, 0, size.x, size.y, size.z, GL_RED_INTEGER,
                        GL_UNSIGNED_BYTE, flags.data());
    return t;
}

} // namespace

void OverlayTextures::updateLeaping(const RenderOverlay& overlay, int cellSize,
                                    glm::ivec3 cellsPerAxis, int brickSize,
                                    glm::ivec3 bricksPerAxis) {
    const auto key =
        std::tuple(fingerprint_, overlay.style.center, overlay.style.width, cellSize, brickSize);
    if (leapingKey_ == key && emptyCells_.get() != 0) {
        return;
    }
    const Volume& v = *overlay.volume;
    emptyCells_ = flagTexture(emptyFlags(v, overlay.style, cellSize, cellsPerAxis), cellsPerAxis);
    emptyBricks_ =
        flagTexture(emptyFlags(v, overlay.style, brickSize, bricksPerAxis), bricksPerAxis);
    checkGl("the overlay's leaping cells");
    leapingKey_ = key;
}

void OverlayTextures::setUniforms(const ShaderProgram& p, const RenderOverlay& overlay) const {
    p.set("uOverlayLow", float(overlay.style.center - 0.5 * overlay.style.width));
    p.set("uOverlayWidth", float(std::max(overlay.style.width, 1e-9)));
    p.set("uOverlayInvDims", 1.0f / glm::vec3(dims_));
}

} // namespace lucent
