#pragma once
// The GPU side of the bricks: one 3D texture cut into slots of
// (brick + 2 * overlap)^3 texels, and which brick sits in which slot
// (BrickSlots decides; this class uploads). Private to render/.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/volume/BrickResidency.h"
#include "render/GlObjects.h"

namespace lucent {

struct TexelFormat {
    GLenum internalFormat = GL_R16_SNORM;
    GLenum uploadType = GL_SHORT; // the client data's type (format GL_RED)
    std::size_t clientBytes = 2;  // per voxel of client data
    std::size_t gpuBytes = 2;     // per texel in the pool
    float valueScale = 32767.0f;  // texture value -> data value
};

class BrickPool {
public:
    // A pool of at least `capacity` slots (fewer only when one 3D texture
    // cannot hold them): as many as its texture's shape holds, up to
    // `maxSlots`. With gradients, a second texture of the same layout holds
    // each slot's gradient (RGBA16 snorm, see extractGradientBrick). Throws
    // GlError when the driver refuses the memory.
    BrickPool(int slotSize, const TexelFormat& format, std::size_t capacity, bool withGradients,
              std::size_t maxSlots);
    static constexpr std::size_t kGradientBytes = 8; // per texel

    int slotSize() const { return slotSize_; }
    const TexelFormat& format() const { return format_; }
    GLuint texture() const { return texture_.get(); }
    GLuint gradientTexture() const { return gradients_.get(); }
    bool hasGradients() const { return gradients_.get() != 0; }
    glm::ivec3 textureSize() const { return slotsPerAxis_ * slotSize_; }
    glm::ivec3 slotOrigin(std::uint32_t slot) const; // in slots
    BrickSlots& slots() { return slots_; }
    std::size_t bytes() const;     // the textures' memory, used slots or not
    std::size_t slotBytes() const; // one slot's texels, values and gradients

    // Takes over a smaller pool's bricks, slot for slot, by copies on the GPU
    // (nothing is uploaded again). Needs the same slot size and format, room
    // for every resident brick, and gradients only where `smaller` has them.
    void adopt(const BrickPool& smaller);
    // Copies one brick's texels (slotSize^3 of the client type) into a slot.
    void upload(std::uint32_t slot, const void* texels);
    // Four int16 per texel (x, y, z, 0).
    void uploadGradients(std::uint32_t slot, const std::int16_t* texels);

    // Extracts each brick (ids in `grid`, with `overlap` = (slotSize - brick) / 2)
    // from `source` and its gradient (when the pool keeps them, in units of
    // gradientUnit), in parallel batches, and uploads them. Returns the bytes sent.
    std::size_t uploadBricks(const std::vector<BrickSlots::Upload>& uploads, const BrickGrid& grid,
                             const Volume& source, BrickEdge edge, double gradientUnit);

private:
    int slotSize_;
    TexelFormat format_;
    bool withGradients_;
    glm::ivec3 slotsPerAxis_{1};
    GlTexture texture_;
    GlTexture gradients_;
    BrickSlots slots_;
};

} // namespace lucent
