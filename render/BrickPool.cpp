#include "render/BrickPool.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "render/GlError.h"

namespace lucent {

namespace {

// The slot grid for `capacity` slots: the fewest slots beyond it within
// maxSlots (the texture takes them all, so this keeps it in the budget), as
// cubic as the texture limit allows among those.
glm::ivec3 slotGrid(std::size_t capacity, std::size_t maxSlots, int slotSize) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSize);
    const int perAxisMax = std::max(1, maxSize / slotSize);
    const std::size_t c = std::max<std::size_t>(capacity, 1);
    glm::ivec3 best(0);
    std::size_t bestCount = 0;
    for (int x = 1; x <= perAxisMax; ++x) {
        for (int y = 1; y <= perAxisMax; ++y) {
            const std::size_t xy = std::size_t(x) * std::size_t(y);
            const std::size_t z = (c + xy - 1) / xy;
            const std::size_t count = xy * z;
            if (z > std::size_t(perAxisMax) || (count > maxSlots && count > c)) {
                continue;
            }
            const int longest = std::max({x, y, int(z)});
            if (bestCount == 0 || count < bestCount ||
                (count == bestCount && longest < std::max({best.x, best.y, best.z}))) {
                best = {x, y, int(z)};
                bestCount = count;
            }
        }
    }
    if (bestCount == 0) { // more than one texture holds: as many as it does
        return glm::ivec3(perAxisMax);
    }
    return best;
}

} // namespace

bool BrickPool::sharesTexture(const TexelFormat& format, bool withGradients) {
    return withGradients && format.internalFormat == GL_R16_SNORM;
}

std::size_t BrickPool::texelBytes(const TexelFormat& format, bool withGradients) {
    if (sharesTexture(format, withGradients)) {
        return kGradientBytes;
    }
    return format.gpuBytes + (withGradients ? kGradientBytes : 0);
}

BrickPool::BrickPool(int slotSize, const TexelFormat& format, std::size_t capacity,
                     bool withGradients, std::size_t maxSlots)
    : slotSize_(slotSize), format_(format), withGradients_(withGradients),
      shared_(sharesTexture(format, withGradients)), slots_(0) {
    slotsPerAxis_ = slotGrid(capacity, maxSlots, slotSize);
    const std::size_t fits =
        std::size_t(slotsPerAxis_.x) * std::size_t(slotsPerAxis_.y) * std::size_t(slotsPerAxis_.z);
    slots_ = BrickSlots(std::min(fits, std::max(capacity, maxSlots)));
    texture_ = makeTexture(GL_TEXTURE_3D);
    const glm::ivec3 size = textureSize();
    glTextureStorage3D(texture_.get(), 1, shared_ ? GL_RGBA16_SNORM : format_.internalFormat,
                       size.x, size.y, size.z);
    checkGl("brick pool of " + std::to_string(size.x) + "x" + std::to_string(size.y) + "x" +
            std::to_string(size.z) + " texels (" + std::to_string(bytes() >> 20) + " MiB)");
    const auto linear = [](GLuint t) {
        glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        for (const GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) {
            glTextureParameteri(t, wrap, GL_CLAMP_TO_EDGE);
        }
    };
    linear(texture_.get());
    if (withGradients && !shared_) {
        gradients_ = makeTexture(GL_TEXTURE_3D);
        glTextureStorage3D(gradients_.get(), 1, GL_RGBA16_SNORM, size.x, size.y, size.z);
        checkGl("gradient pool (" + std::to_string(bytes() >> 20) + " MiB with the values)");
        linear(gradients_.get());
    }
}

std::size_t BrickPool::slotBytes() const {
    return std::size_t(slotSize_) * slotSize_ * slotSize_ * texelBytes(format_, withGradients_);
}

std::size_t BrickPool::bytes() const {
    const glm::ivec3 s = textureSize();
    return std::size_t(s.x) * std::size_t(s.y) * std::size_t(s.z) *
           texelBytes(format_, withGradients_);
}

glm::ivec3 BrickPool::slotOrigin(std::uint32_t slot) const {
    const int x = int(slot % std::uint32_t(slotsPerAxis_.x));
    const int y = int((slot / std::uint32_t(slotsPerAxis_.x)) % std::uint32_t(slotsPerAxis_.y));
    const int z = int(slot / std::uint32_t(slotsPerAxis_.x * slotsPerAxis_.y));
    return {x, y, z};
}

bool BrickPool::canAdopt(const BrickPool& smaller) const {
    return smaller.slotSize_ == slotSize_ &&
           smaller.format_.internalFormat == format_.internalFormat && smaller.shared_ == shared_ &&
           (smaller.withGradients_ || !withGradients_) &&
           smaller.slots_.resident() <= slots_.capacity();
}

void BrickPool::adopt(const BrickPool& smaller) {
    if (!canAdopt(smaller)) {
        throw std::logic_error("a brick pool can adopt only a smaller pool of the same kind");
    }
    const std::size_t resident = smaller.slots_.resident();
    for (std::uint32_t slot = 0; slot < resident; ++slot) {
        const glm::ivec3 from = smaller.slotOrigin(slot) * slotSize_;
        const glm::ivec3 to = slotOrigin(slot) * slotSize_;
        glCopyImageSubData(smaller.texture(), GL_TEXTURE_3D, 0, from.x, from.y, from.z, texture(),
                           GL_TEXTURE_3D, 0, to.x, to.y, to.z, slotSize_, slotSize_, slotSize_);
        if (withGradients_ && !shared_) {
            glCopyImageSubData(smaller.gradientTexture(), GL_TEXTURE_3D, 0, from.x, from.y, from.z,
                               gradientTexture(), GL_TEXTURE_3D, 0, to.x, to.y, to.z, slotSize_,
                               slotSize_, slotSize_);
        }
    }
    slots_ = smaller.slots_.withCapacity(slots_.capacity());
    checkGl("moving " + std::to_string(resident) + " bricks into a larger pool");
}

void BrickPool::uploadGradients(std::uint32_t slot, const std::int16_t* texels) {
    const glm::ivec3 at = slotOrigin(slot) * slotSize_;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage3D(gradientTexture(), 0, at.x, at.y, at.z, slotSize_, slotSize_, slotSize_,
                        GL_RGBA, GL_SHORT, texels);
}

void BrickPool::upload(std::uint32_t slot, const void* texels) {
    const glm::ivec3 at = slotOrigin(slot) * slotSize_;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage3D(texture_.get(), 0, at.x, at.y, at.z, slotSize_, slotSize_, slotSize_,
                        GL_RED, format_.uploadType, texels);
}

std::size_t BrickPool::uploadBricks(const std::vector<BrickSlots::Upload>& uploads,
                                    const BrickGrid& grid, const Volume& source, BrickEdge edge,
                                    double gradientUnit) {
    constexpr std::size_t kBatch = 16; // bricks extracted at once: a few tens of MB of staging
    const int overlap = grid.overlap();
    const std::size_t texels = std::size_t(slotSize_) * slotSize_ * slotSize_;
    const std::size_t batch = std::min(uploads.size(), kBatch);
    std::vector<std::byte> staging(batch * texels * format_.clientBytes);
    std::vector<std::int16_t> gradients(hasGradients() ? batch * texels * 4 : 0);
    for (std::size_t first = 0; first < uploads.size(); first += kBatch) {
        const std::size_t count = std::min(kBatch, uploads.size() - first);
        visitVoxels(source, [&](auto voxels) {
            using T = std::remove_const_t<typename decltype(voxels)::element_type>;
            T* dst = reinterpret_cast<T*>(staging.data());
#pragma omp parallel for schedule(dynamic)
            for (std::size_t n = 0; n < count; ++n) {
                const Brick& b = grid.bricks()[std::uint32_t(uploads[first + n].key)];
                T* values = dst + n * texels;
                extractBrick<T>(voxels.data(), source.dims(), b.first, overlap, slotSize_, edge,
                                values);
                if (hasGradients()) {
                    std::int16_t* g = gradients.data() + n * texels * 4;
                    extractGradientBrick<T>(voxels.data(), source.dims(), b.first, overlap,
                                            slotSize_, gradientUnit, g);
                    if constexpr (std::is_same_v<T, std::int16_t>) {
                        if (shared_) {
                            for (std::size_t t = 0; t < texels; ++t) {
                                g[4 * t + 3] = values[t];
                            }
                        }
                    }
                }
            }
        });
        for (std::size_t n = 0; n < count; ++n) {
            if (!shared_) {
                upload(uploads[first + n].slot, staging.data() + n * texels * format_.clientBytes);
            }
            if (hasGradients()) {
                uploadGradients(uploads[first + n].slot, gradients.data() + n * texels * 4);
            }
        }
        checkGl("uploading bricks");
    }
    return uploads.size() * texels *
           (shared_ ? kGradientBytes : format_.clientBytes + (hasGradients() ? kGradientBytes : 0));
}

} // namespace lucent
