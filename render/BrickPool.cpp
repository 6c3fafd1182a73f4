#include "render/BrickPool.h"

#include <algorithm>
#include <string>
#include <type_traits>

#include "render/GlError.h"

namespace lucent {

namespace {

std::size_t volumeOf(glm::ivec3 s) {
    return std::size_t(s.x) * std::size_t(s.y) * std::size_t(s.z);
}

bool holds(const StoredBox& outer, const StoredBox& inner) {
    return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) &&
           glm::all(glm::greaterThanEqual(outer.lo + outer.size, inner.lo + inner.size));
}

void linearFiltering(GLuint t) {
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (const GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) {
        glTextureParameteri(t, wrap, GL_CLAMP_TO_EDGE);
    }
}

// Zero in every texel: glClearTexImage where the context has it (4.4), else
// zeros uploaded a slice at a time.
void clearToZero(GLuint t, glm::ivec3 size, GLenum format, GLenum type, std::size_t texelBytes) {
    if (epoxy_gl_version() >= 44 || epoxy_has_gl_extension("GL_ARB_clear_texture")) {
        glClearTexImage(t, 0, format, type, nullptr);
        return;
    }
    const std::vector<std::byte> zeros(std::size_t(size.x) * std::size_t(size.y) * texelBytes);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int z = 0; z < size.z; ++z) {
        glTextureSubImage3D(t, 0, 0, 0, z, size.x, size.y, 1, format, type, zeros.data());
    }
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

BrickPool::BrickPool(const TexelFormat& format, bool withGradients, glm::ivec3 extent)
    : format_(format), withGradients_(withGradients), shared_(sharesTexture(format, withGradients)),
      atlas_(extent) {
    const auto describe = [&] {
        return std::to_string(extent.x) + "x" + std::to_string(extent.y) + "x" +
               std::to_string(extent.z) + " texels (" + std::to_string(bytes() >> 20) + " MiB)";
    };
    values_ = makeTexture(GL_TEXTURE_3D);
    glTextureStorage3D(values_.get(), 1, shared_ ? GL_RGBA16_SNORM : format_.internalFormat,
                       extent.x, extent.y, extent.z);
    checkGl("brick pool of " + describe());
    linearFiltering(values_.get());
    if (shared_) {
        clearToZero(values_.get(), extent, GL_RGBA, GL_SHORT, 8);
    } else {
        clearToZero(values_.get(), extent, GL_RED, format_.uploadType, format_.clientBytes);
    }
    if (withGradients && !shared_) {
        gradients_ = makeTexture(GL_TEXTURE_3D);
        glTextureStorage3D(gradients_.get(), 1, GL_RGBA16_SNORM, extent.x, extent.y, extent.z);
        checkGl("gradient pool, with the values " + describe());
        linearFiltering(gradients_.get());
        clearToZero(gradients_.get(), extent, GL_RGBA, GL_SHORT, 8);
    }
    checkGl("clearing the brick pool");
}

std::size_t BrickPool::bytes() const {
    return atlas_.texels() * texelBytes(format_, withGradients_);
}

bool BrickPool::sameKind(const BrickPool& other) const {
    return other.format_.internalFormat == format_.internalFormat &&
           other.withGradients_ == withGradients_ && other.shared_ == shared_;
}

const BrickPool::Entry* BrickPool::find(int level, std::uint32_t brick,
                                        const StoredBox& needed) const {
    const auto it = entries_.find(key(level, brick));
    return it != entries_.end() && holds(it->second.box, needed) ? &it->second : nullptr;
}

void BrickPool::touch(int level, std::uint32_t brick, std::uint64_t frame) {
    const auto it = entries_.find(key(level, brick));
    if (it != entries_.end()) {
        it->second.lastUse = frame;
    }
}

void BrickPool::remove(std::uint64_t k) {
    const auto it = entries_.find(k);
    if (it != entries_.end()) {
        atlas_.release(it->second.at, it->second.box.size);
        entries_.erase(it);
    }
}

std::optional<glm::ivec3> BrickPool::place(const StoredBox& box, std::uint64_t frame) {
    if (auto at = atlas_.place(box.size)) {
        return at;
    }
    std::vector<std::pair<std::uint64_t, std::uint64_t>> old; // last use, key
    for (const auto& [k, e] : entries_) {
        if (e.lastUse < frame) {
            old.emplace_back(e.lastUse, k);
        }
    }
    std::sort(old.begin(), old.end());
    for (const auto& [use, k] : old) {
        remove(k);
        if (auto at = atlas_.place(box.size)) {
            return at;
        }
    }
    return std::nullopt;
}

std::size_t BrickPool::upload(const std::vector<Upload>& uploads, const Volume& source,
                              BrickEdge edge, double gradientUnit, std::uint64_t frame) {
    constexpr std::size_t kBatch = 16; // boxes extracted at once: a few tens of MB of staging
    std::size_t sent = 0;
    std::vector<std::vector<std::byte>> values(std::min(uploads.size(), kBatch));
    std::vector<std::vector<std::int16_t>> gradients(values.size());
    for (std::size_t first = 0; first < uploads.size(); first += kBatch) {
        const std::size_t count = std::min(kBatch, uploads.size() - first);
        visitVoxels(source, [&](auto voxels) {
            using T = std::remove_const_t<typename decltype(voxels)::element_type>;
#pragma omp parallel for schedule(dynamic)
            for (std::size_t n = 0; n < count; ++n) {
                const StoredBox& b = uploads[first + n].box;
                const std::size_t texels = volumeOf(b.size);
                values[n].resize(texels * sizeof(T));
                T* out = reinterpret_cast<T*>(values[n].data());
                extractBox<T>(voxels.data(), source.dims(), b.lo, b.size, edge, out);
                if (withGradients_) {
                    gradients[n].resize(4 * texels);
                    std::int16_t* g = gradients[n].data();
                    extractGradientBox<T>(voxels.data(), source.dims(), b.lo, b.size, gradientUnit,
                                          g);
                    if constexpr (std::is_same_v<T, std::int16_t>) {
                        if (shared_) { // the value rides in the gradient texel's alpha
                            for (std::size_t t = 0; t < texels; ++t) {
                                g[4 * t + 3] = out[t];
                            }
                        }
                    }
                }
            }
        });
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        for (std::size_t n = 0; n < count; ++n) {
            const Upload& u = uploads[first + n];
            const glm::ivec3 s = u.box.size;
            if (!shared_) {
                glTextureSubImage3D(values_.get(), 0, u.at.x, u.at.y, u.at.z, s.x, s.y, s.z, GL_RED,
                                    format_.uploadType, values[n].data());
                sent += values[n].size();
            }
            if (withGradients_) {
                glTextureSubImage3D(gradientTexture(), 0, u.at.x, u.at.y, u.at.z, s.x, s.y, s.z,
                                    GL_RGBA, GL_SHORT, gradients[n].data());
                sent += gradients[n].size() * sizeof(std::int16_t);
            }
            const std::uint64_t k = key(u.level, u.brick);
            const auto old = entries_.find(k);
            if (old != entries_.end()) { // a smaller box of the same brick: its room is free
                atlas_.release(old->second.at, old->second.box.size);
                entries_.erase(old);
            }
            entries_[k] = Entry{u.level, u.brick, u.box, u.at, frame};
        }
        checkGl("uploading bricks");
    }
    return sent;
}

void BrickPool::copyFrom(const BrickPool& other, const Entry& e, glm::ivec3 at,
                         std::uint64_t frame) {
    const glm::ivec3 s = e.box.size;
    glCopyImageSubData(other.values_.get(), GL_TEXTURE_3D, 0, e.at.x, e.at.y, e.at.z, values_.get(),
                       GL_TEXTURE_3D, 0, at.x, at.y, at.z, s.x, s.y, s.z);
    if (withGradients_ && !shared_) {
        glCopyImageSubData(other.gradients_.get(), GL_TEXTURE_3D, 0, e.at.x, e.at.y, e.at.z,
                           gradients_.get(), GL_TEXTURE_3D, 0, at.x, at.y, at.z, s.x, s.y, s.z);
    }
    Entry copy = e;
    copy.at = at;
    copy.lastUse = frame;
    entries_[key(e.level, e.brick)] = copy;
}

} // namespace lucent
