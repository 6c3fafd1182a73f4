#pragma once
// The GPU side of the bricks: one 3D texture cut into slots of
// (brick + 2 * overlap)^3 texels, and which brick sits in which slot
// (BrickSlots decides; this class uploads). Private to render/.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/volume/BrickResidency.h"
#include "render/GlObjects_p.h"

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
    // `maxSlots`. With gradients, each texel also holds the gradient there
    // (RGBA16 snorm, see extractGradientBrick): for int16 voxels in one
    // texture (x, y, z, value), so a shaded sample reads one texel; for other
    // types in a second texture of the same layout. Throws GlError when the
    // driver refuses the memory.
    BrickPool(int slotSize, const TexelFormat& format, std::size_t capacity, bool withGradients,
              std::size_t maxSlots);
    static constexpr std::size_t kGradientBytes = 8; // per texel
    // GPU bytes one texel takes in such a pool, values and gradients.
    static std::size_t texelBytes(const TexelFormat& format, bool withGradients);
    // Whether values and gradients share one RGBA texture (value in alpha).
    static bool sharesTexture(const TexelFormat& format, bool withGradients);

    int slotSize() const { return slotSize_; }
    const TexelFormat& format() const { return format_; }
    GLuint texture() const { return texture_.get(); }
    GLuint gradientTexture() const { return shared_ ? texture_.get() : gradients_.get(); }
    bool hasGradients() const { return withGradients_; }
    bool gradientsShareTexture() const { return shared_; }
    glm::ivec3 textureSize() const { return slotsPerAxis_ * slotSize_; }
    glm::ivec3 slotOrigin(std::uint32_t slot) const; // in slots
    BrickSlots& slots() { return slots_; }
    std::size_t bytes() const;     // the textures' memory, used slots or not
    std::size_t slotBytes() const; // one slot's texels, values and gradients

    // Whether adopt can take over `smaller`'s bricks: the same slot size and
    // texture layout (gradients dropped from a second texture are fine), and
    // room for every resident brick.
    bool canAdopt(const BrickPool& smaller) const;
    // Takes over those bricks, slot for slot, by copies on the GPU (nothing
    // is uploaded again). Throws std::logic_error where canAdopt says no.
    void adopt(const BrickPool& smaller);
    // Copies one brick's texels (slotSize^3 of the client type) into a slot.
    void upload(std::uint32_t slot, const void* texels);
    // Four int16 per texel (x, y, z, 0; or x, y, z, value where they share a texture).
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
    bool shared_;
    glm::ivec3 slotsPerAxis_{1};
    GlTexture texture_;
    GlTexture gradients_;
    BrickSlots slots_;
};

} // namespace lucent
