#include "core/volume/BrickResidency.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/volume/LodPyramid.h"

namespace lucent {

namespace {

ClipBox clipAtLevel(const ClipBox& clip, int level) {
    const double f = std::ldexp(1.0, level), c = (f - 1.0) * 0.5;
    ClipBox out;
    for (int a = 0; a < 3; ++a) {
        // The default box is +-1e300: keep it unbounded rather than scale it.
        out.lo[a] = std::abs(clip.lo[a]) > 1e290 ? clip.lo[a] : (clip.lo[a] - c) / f;
        out.hi[a] = std::abs(clip.hi[a]) > 1e290 ? clip.hi[a] : (clip.hi[a] - c) / f;
    }
    return out;
}

int mirrorIndex(int i, int n) {
    if (n == 1) {
        return 0;
    }
    const int period = 2 * (n - 1);
    i = ((i % period) + period) % period;
    return i < n ? i : period - i;
}

} // namespace

ResidencyPlan planResidency(const std::vector<const BrickGrid*>& levels,
                            const std::function<bool(double, double)>& isVisible,
                            const ClipBox& clip, bool withNeighbours, std::size_t slots,
                            const BoxTest& inView) {
    std::vector<std::size_t> rejected;
    for (std::size_t n = 0; n < levels.size(); ++n) {
        const BrickGrid& grid = *levels[n];
        std::vector<std::uint32_t> needed =
            visibleBricks(grid, isVisible, clipAtLevel(clip, int(n)));
        if (inView) {
            // A sample lies in the brick whose core holds it (half a voxel of slack).
            std::erase_if(needed, [&](std::uint32_t id) {
                const Brick& b = grid.bricks()[id];
                return !inView(LodPyramid::toLevel0(glm::dvec3(b.first) - 0.5, int(n)),
                               LodPyramid::toLevel0(glm::dvec3(b.last) - 0.5, int(n)));
            });
        }
        ResidencyPlan plan;
        plan.level = int(n);
        plan.needed = needed.size();
        std::vector<std::uint8_t> mark(grid.count(), 0); // 2 needed, 1 neighbour
        for (const std::uint32_t id : needed) {
            mark[id] = 2;
        }
        if (withNeighbours) {
            const glm::ivec3 per = grid.bricksPerAxis();
            for (const std::uint32_t id : needed) {
                const glm::ivec3 b = grid.bricks()[id].index;
                for (int dz = -1; dz <= 1; ++dz) {
                    for (int dy = -1; dy <= 1; ++dy) {
                        for (int dx = -1; dx <= 1; ++dx) {
                            const glm::ivec3 q = b + glm::ivec3(dx, dy, dz);
                            if (glm::all(glm::greaterThanEqual(q, glm::ivec3(0))) &&
                                glm::all(glm::lessThan(q, per))) {
                                std::uint8_t& m = mark[grid.idOf(q)];
                                m = std::max<std::uint8_t>(m, 1);
                            }
                        }
                    }
                }
            }
        }
        for (std::uint32_t id = 0; id < mark.size(); ++id) {
            if (mark[id] != 0) {
                plan.bricks.push_back(id);
                plan.leapable.push_back(mark[id] == 1 ? 1 : 0);
            }
        }
        if (plan.bricks.size() <= slots) {
            plan.rejected = std::move(rejected);
            return plan;
        }
        rejected.push_back(plan.bricks.size());
    }
    throw BudgetError("the GPU budget holds " + std::to_string(slots) + " bricks, but level " +
                      std::to_string(levels.size() - 1) + ", the coarsest tried, needs " +
                      std::to_string(rejected.empty() ? 0 : rejected.back()));
}

std::vector<BrickSlots::Upload> BrickSlots::acquire(const std::vector<std::uint64_t>& keys) {
    if (keys.size() > capacity_) {
        throw std::length_error(std::to_string(keys.size()) + " bricks for a pool of " +
                                std::to_string(capacity_) + " slots");
    }
    ++clock_;
    std::vector<std::uint64_t> missing;
    for (const std::uint64_t k : keys) {
        const auto it = slotOfKey_.find(k);
        if (it != slotOfKey_.end()) {
            lastUse_[it->second] = clock_;
        } else {
            missing.push_back(k);
        }
    }
    std::vector<Upload> uploads;
    if (missing.empty()) {
        return uploads;
    }
    // Free slots first, then the least recently used that this render does not need.
    std::vector<std::uint32_t> victims;
    const std::size_t fresh = std::min(capacity_ - keyOfSlot_.size(), missing.size());
    if (fresh < missing.size()) {
        std::vector<std::uint32_t> old;
        for (std::uint32_t s = 0; s < keyOfSlot_.size(); ++s) {
            if (lastUse_[s] != clock_) {
                old.push_back(s);
            }
        }
        const std::size_t want = missing.size() - fresh;
        std::partial_sort(
            old.begin(), old.begin() + std::ptrdiff_t(want), old.end(),
            [&](std::uint32_t a, std::uint32_t b) { return lastUse_[a] < lastUse_[b]; });
        victims.assign(old.begin(), old.begin() + std::ptrdiff_t(want));
    }
    std::size_t nextVictim = 0;
    for (const std::uint64_t k : missing) {
        std::uint32_t slot = 0;
        if (keyOfSlot_.size() < capacity_) {
            slot = std::uint32_t(keyOfSlot_.size());
            keyOfSlot_.push_back(k);
            lastUse_.push_back(clock_);
        } else {
            slot = victims[nextVictim++];
            slotOfKey_.erase(keyOfSlot_[slot]);
            keyOfSlot_[slot] = k;
            lastUse_[slot] = clock_;
        }
        slotOfKey_[k] = slot;
        uploads.push_back({k, slot});
    }
    return uploads;
}

BrickSlots BrickSlots::withCapacity(std::size_t capacity) const {
    if (capacity < resident()) {
        throw std::length_error(std::to_string(resident()) + " resident bricks for a pool of " +
                                std::to_string(capacity) + " slots");
    }
    BrickSlots out = *this;
    out.capacity_ = capacity;
    return out;
}

std::optional<std::uint32_t> BrickSlots::slotOf(std::uint64_t key) const {
    const auto it = slotOfKey_.find(key);
    if (it == slotOfKey_.end()) {
        return std::nullopt;
    }
    return it->second;
}

template <class T>
void extractBrick(const T* data, glm::ivec3 dims, glm::ivec3 first, int overlap, int slotSize,
                  BrickEdge edge, T* out) {
    const auto index = [&](int i, int n) {
        return edge == BrickEdge::Clamp ? std::clamp(i, 0, n - 1) : mirrorIndex(i, n);
    };
    const glm::ivec3 start = first - overlap;
    std::vector<int> xs(std::size_t(slotSize), 0);
    for (int a = 0; a < slotSize; ++a) {
        xs[std::size_t(a)] = index(start.x + a, dims.x);
    }
    const bool inside = start.x >= 0 && start.x + slotSize <= dims.x;
    for (int c = 0; c < slotSize; ++c) {
        const std::size_t k = std::size_t(index(start.z + c, dims.z));
        for (int b = 0; b < slotSize; ++b) {
            const std::size_t j = std::size_t(index(start.y + b, dims.y));
            const T* row = data + std::size_t(dims.x) * (j + std::size_t(dims.y) * k);
            T* dst = out + std::size_t(slotSize) * (std::size_t(b) + std::size_t(slotSize) * c);
            if (inside) {
                std::copy(row + start.x, row + start.x + slotSize, dst);
            } else {
                for (int a = 0; a < slotSize; ++a) {
                    dst[a] = row[xs[std::size_t(a)]];
                }
            }
        }
    }
}

template <class T>
void extractGradientBrick(const T* data, glm::ivec3 dims, glm::ivec3 first, int overlap,
                          int slotSize, double unit, std::int16_t* out) {
    const glm::ivec3 start = first - overlap;
    const double inverse = 0.5 / unit;
    const auto quantised = [&](double d) {
        return std::int16_t(std::clamp(std::lround(d * inverse), -32767L, 32767L));
    };
    // Every index clamped to the volume, the neighbours' too, worked out once
    // per axis: the inner loop reads rows without a clamp.
    const auto clamped = [&](int i, int n) { return std::clamp(i, 0, n - 1); };
    const std::size_t n = std::size_t(slotSize);
    std::vector<int> xs(n, 0), xm(n, 0), xp(n, 0);
    for (int a = 0; a < slotSize; ++a) {
        const int i = clamped(start.x + a, dims.x);
        xs[std::size_t(a)] = i;
        xm[std::size_t(a)] = clamped(i - 1, dims.x);
        xp[std::size_t(a)] = clamped(i + 1, dims.x);
    }
    const auto row = [&](int j, int k) {
        return data + std::size_t(dims.x) * (std::size_t(j) + std::size_t(dims.y) * std::size_t(k));
    };
    for (int c = 0; c < slotSize; ++c) {
        const int k = clamped(start.z + c, dims.z);
        for (int b = 0; b < slotSize; ++b) {
            const int j = clamped(start.y + b, dims.y);
            const T* here = row(j, k);
            const T* jm = row(clamped(j - 1, dims.y), k);
            const T* jp = row(clamped(j + 1, dims.y), k);
            const T* km = row(j, clamped(k - 1, dims.z));
            const T* kp = row(j, clamped(k + 1, dims.z));
            std::int16_t* dst =
                out + 4 * std::size_t(slotSize) * (std::size_t(b) + std::size_t(slotSize) * c);
            for (std::size_t a = 0; a < std::size_t(slotSize); ++a) {
                const int i = xs[a];
                dst[4 * a + 0] = quantised(double(here[xp[a]]) - double(here[xm[a]]));
                dst[4 * a + 1] = quantised(double(jp[i]) - double(jm[i]));
                dst[4 * a + 2] = quantised(double(kp[i]) - double(km[i]));
                dst[4 * a + 3] = 0;
            }
        }
    }
}

template void extractGradientBrick<std::int16_t>(const std::int16_t*, glm::ivec3, glm::ivec3, int,
                                                 int, double, std::int16_t*);
template void extractGradientBrick<std::uint16_t>(const std::uint16_t*, glm::ivec3, glm::ivec3, int,
                                                  int, double, std::int16_t*);
template void extractGradientBrick<float>(const float*, glm::ivec3, glm::ivec3, int, int, double,
                                          std::int16_t*);

template void extractBrick<std::int16_t>(const std::int16_t*, glm::ivec3, glm::ivec3, int, int,
                                         BrickEdge, std::int16_t*);
template void extractBrick<std::uint16_t>(const std::uint16_t*, glm::ivec3, glm::ivec3, int, int,
                                          BrickEdge, std::uint16_t*);
template void extractBrick<float>(const float*, glm::ivec3, glm::ivec3, int, int, BrickEdge,
                                  float*);

} // namespace lucent
