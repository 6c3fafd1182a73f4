#pragma once
// Empty-space leaping for a fused DVR render (CpuRayCaster): a brick or cell is passed over
// only where the base's classification passes it over and the overlay shows nothing there:
// every overlay voxel its samples can read (the core and the overlap, as BrickGrid bounds
// them; NaN ignored) lies below the window's first visible entry (windowToGrey's entry 1,
// low + width / 510), with a margin for the float rounding of a trilinear sample. So leaping
// still changes no pixel. Private to core/raycast.

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "core/fusion/FusionStyle.h"
#include "core/volume/BrickGrid.h"
#include "core/volume/Volume.h"

namespace lucent {

class OverlayLeaping {
public:
    // baseSkippable (one flag per brick of `layout`) and'ed with the overlay's emptiness
    // under `style`'s window, for the leaping level `level` (0 bricks, 1 cells). The
    // overlay's brick bounds are kept per brick size and overlap while the overlay's
    // fingerprint (OverlaySampler.h) stays the same.
    const std::vector<std::uint8_t>& skippable(const Volume& overlay, const FusionStyle& style,
                                               const BrickGrid& layout,
                                               const std::vector<std::uint8_t>& baseSkippable,
                                               int level);

private:
    std::uint64_t fingerprint_ = 0;
    std::map<std::pair<int, int>, BrickGrid> grids_; // (brick size, overlap)
    std::vector<std::uint8_t> levels_[2];
};

} // namespace lucent
