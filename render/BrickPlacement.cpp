#include "render/BrickPlacement.h"

#include <algorithm>
#include <string>

#include "render/GlError.h"

namespace lucent {

std::size_t volumeOf(glm::ivec3 s) {
    return std::size_t(s.x) * std::size_t(s.y) * std::size_t(s.z);
}

namespace {

// Packing order: the longest side first, then the volume.
bool largerBox(glm::ivec3 a, glm::ivec3 b) {
    const int ma = std::max({a.x, a.y, a.z}), mb = std::max({b.x, b.y, b.z});
    return ma > mb || (ma == mb && volumeOf(a) > volumeOf(b));
}

// A new atlas for the frame's boxes, at least half as large again as the
// old one (within the budget), packed largest first: resident boxes copied
// over on the GPU, the others placed for upload.
Placements repack(std::unique_ptr<BrickPool>& pool, const std::vector<Shown>& shown,
                  std::size_t budget, std::uint64_t frame) {
    const std::size_t texelBytes = BrickPool::texelBytes(pool->format(), pool->hasGradients());
    // Per shown brick: the box it takes (a resident one may be larger than planned).
    std::vector<std::size_t> items;
    std::vector<glm::ivec3> sizes(shown.size(), glm::ivec3(0));
    std::vector<const BrickPool::Entry*> resident(shown.size(), nullptr);
    std::size_t need = 0;
    glm::ivec3 largest(1);
    for (std::size_t n = 0; n < shown.size(); ++n) {
        if (shown[n].level < 0) {
            continue;
        }
        if (!shown[n].upload) {
            resident[n] = pool->find(shown[n].level, shown[n].id, shown[n].stored);
        }
        sizes[n] = resident[n] ? resident[n]->box.size : shown[n].stored.size;
        items.push_back(n);
        need += volumeOf(sizes[n]);
        largest = glm::max(largest, sizes[n]);
    }
    std::stable_sort(items.begin(), items.end(),
                     [&](std::size_t a, std::size_t b) { return largerBox(sizes[a], sizes[b]); });
    GLint maxSide = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &maxSide);
    const std::size_t cap = budget / texelBytes;
    // A pool that held bricks before grows by half, so that it is not
    // repacked again at the next transfer function; a new one by what it needs.
    const bool grown = pool->residentCount() > 0;
    std::size_t target =
        std::min(std::max(need + need / 8, grown ? volumeOf(pool->extent()) * 3 / 2 : 0), cap);
    for (;;) {
        const glm::ivec3 extent =
            BoxAtlas::extentFor(std::max(target, need), largest, int(maxSide), cap);
        BoxAtlas trial(extent);
        std::vector<glm::ivec3> at;
        for (const std::size_t n : items) {
            const auto o = trial.place(sizes[n]);
            if (!o) {
                break;
            }
            at.push_back(*o);
        }
        if (at.size() < items.size()) {
            if (target >= cap) {
                throw PackingError("the frame's " + std::to_string(items.size()) +
                                   " bricks do not pack into the budget of " +
                                   std::to_string(budget >> 20) + " MiB");
            }
            target = std::min(cap, target + target / 8 + 1);
            continue;
        }
        auto fresh = std::make_unique<BrickPool>(pool->format(), pool->hasGradients(), extent);
        Placements uploads;
        for (std::size_t m = 0; m < items.size(); ++m) {
            const std::size_t n = items[m];
            // The same boxes in the same order land where the trial put them.
            const glm::ivec3 o = fresh->place({glm::ivec3(0), sizes[n]}, frame).value_or(at[m]);
            if (resident[n]) {
                fresh->copyFrom(*pool, *resident[n], o, frame);
            } else {
                uploads.emplace_back(n, o);
            }
        }
        checkGl("moving the resident bricks into a new atlas");
        pool = std::move(fresh);
        return uploads;
    }
}

} // namespace

Placements placeUploads(std::unique_ptr<BrickPool>& pool, const std::vector<Shown>& shown,
                        std::size_t budget, std::uint64_t frame) {
    std::vector<std::size_t> toPlace;
    for (std::size_t n = 0; n < shown.size(); ++n) {
        if (shown[n].upload) {
            toPlace.push_back(n);
        }
    }
    std::stable_sort(toPlace.begin(), toPlace.end(), [&](std::size_t a, std::size_t b) {
        return largerBox(shown[a].stored.size, shown[b].stored.size);
    });
    Placements placed;
    for (const std::size_t n : toPlace) {
        const auto at = pool->place(shown[n].stored, frame);
        if (!at) {
            return repack(pool, shown, budget, frame);
        }
        placed.emplace_back(n, *at);
    }
    return placed;
}

} // namespace lucent
