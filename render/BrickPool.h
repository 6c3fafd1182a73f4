#pragma once
// The GPU side of the bricks: a 3D texture atlas holding each resident
// brick's box of voxels (tight bricks: only what the scene can read, see
// core/volume/BrickBoxes.h) at the level it is drawn from, with their
// gradients when the pool keeps them (RGBA16 snorm): for int16 voxels in the
// same texel (x, y, z, value), so that a shaded sample reads one texel; for
// other types in a second texture of the same layout. Where each box sits is the BoxAtlas's
// decision; bricks the current frame does not use stay until their room is
// needed, least recently used first. Private to render/.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "core/volume/BoxAtlas.h"
#include "core/volume/BrickBoxes.h"
#include "core/volume/BrickResidency.h"
#include "core/volume/Volume.h"
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
    static constexpr std::size_t kGradientBytes = 8; // per texel: RGBA16 snorm

    struct Entry {
        int level = 0;
        std::uint32_t brick = 0; // id in the level-0 brick grid
        StoredBox box;           // the level's voxels it holds
        glm::ivec3 at{0};        // where they start in the atlas
        std::uint64_t lastUse = 0;
    };
    // A box to upload for a brick at a level, and where it goes (place()).
    struct Upload {
        int level = 0;
        std::uint32_t brick = 0;
        StoredBox box;
        glm::ivec3 at{0};
    };

    // An atlas of `extent` texels, cleared to zero (so that a filter weight
    // of zero on a neighbour's texel never meets a NaN). Throws GlError (or
    // GlOutOfMemory) when the driver refuses the memory.
    BrickPool(const TexelFormat& format, bool withGradients, glm::ivec3 extent);
    // GPU bytes one texel takes, values and gradients.
    static std::size_t texelBytes(const TexelFormat& format, bool withGradients);
    // Whether values and gradients share one RGBA texture (value in alpha).
    static bool sharesTexture(const TexelFormat& format, bool withGradients);

    const TexelFormat& format() const { return format_; }
    bool hasGradients() const { return withGradients_; }
    GLuint texture() const { return values_.get(); }
    GLuint gradientTexture() const { return shared_ ? values_.get() : gradients_.get(); }
    bool gradientsShareTexture() const { return shared_; }
    glm::ivec3 extent() const { return atlas_.extent(); }
    std::size_t bytes() const; // the textures' memory, used or not
    std::size_t residentTexels() const { return atlas_.usedTexels(); }
    std::size_t residentCount() const { return entries_.size(); }

    // The entry of a brick at a level, if it is resident and its box holds `needed`.
    const Entry* find(int level, std::uint32_t brick, const StoredBox& needed) const;
    // Marks an entry used by frame `frame` (kept before those that are not).
    void touch(int level, std::uint32_t brick, std::uint64_t frame);
    // Room for a box, evicting entries last used before `frame` (oldest
    // first) as needed; nothing when even that leaves none.
    std::optional<glm::ivec3> place(const StoredBox& box, std::uint64_t frame);
    // Extracts the boxes from `source` (a level's voxels or spline
    // coefficients), with gradients in units of gradientUnit where the pool
    // keeps them, in parallel batches, and uploads them; replaces any older
    // entry of the same brick and level. Returns the bytes sent.
    std::size_t upload(const std::vector<Upload>& uploads, const Volume& source, BrickEdge edge,
                       double gradientUnit, std::uint64_t frame);
    // Copies an entry of another pool of the same kind into this one, on the
    // GPU, at `at` (from place()).
    void copyFrom(const BrickPool& other, const Entry& entry, glm::ivec3 at, std::uint64_t frame);
    bool sameKind(const BrickPool& other) const;
    const std::unordered_map<std::uint64_t, Entry>& entries() const { return entries_; }

private:
    static std::uint64_t key(int level, std::uint32_t brick) {
        return (std::uint64_t(std::uint32_t(level)) << 32) | brick;
    }
    void remove(std::uint64_t key);

    TexelFormat format_;
    bool withGradients_;
    bool shared_;
    BoxAtlas atlas_;
    GlTexture values_;
    GlTexture gradients_;
    std::unordered_map<std::uint64_t, Entry> entries_;
};

} // namespace lucent
