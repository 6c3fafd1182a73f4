#include "core/raycast/OverlayLeaping.h"

#include <cmath>
#include <stdexcept>

#include "core/raycast/OverlaySampler.h"

namespace lucent {

const std::vector<std::uint8_t>&
OverlayLeaping::skippable(const Volume& overlay, const FusionStyle& style, const BrickGrid& layout,
                          const std::vector<std::uint8_t>& baseSkippable, int level) {
    const std::uint64_t fingerprint = overlayFingerprint(overlay);
    if (fingerprint != fingerprint_) {
        grids_.clear();
        fingerprint_ = fingerprint;
    }
    const auto key = std::pair(layout.brickSize(), layout.overlap());
    auto it = grids_.find(key);
    if (it == grids_.end()) {
        it = grids_.emplace(key, BrickGrid(overlay, key.first, key.second)).first;
    }
    const BrickGrid& grid = it->second;
    if (grid.count() != layout.count() || baseSkippable.size() != layout.count()) {
        throw std::logic_error("overlay leaping: the overlay's bricks are not the base's");
    }
    // Entry i >= 1 from (v - low) / width * 255 >= 0.5 on (windowToGrey's rounding).
    const double low = style.center - 0.5 * style.width;
    const double first = low + 0.5 * style.width / 255.0;
    const double margin = 1e-5 * (std::abs(low) + std::abs(style.width) + 1.0);
    std::vector<std::uint8_t>& out = levels_[level == 0 ? 0 : 1];
    out.assign(layout.count(), 0);
    for (std::size_t i = 0; i < layout.count(); ++i) {
        const bool overlayEmpty = double(grid.bricks()[i].maxValue) < first - margin;
        out[i] = baseSkippable[i] != 0 && overlayEmpty ? 1 : 0;
    }
    return out;
}

} // namespace lucent
