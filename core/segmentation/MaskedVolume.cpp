#include "core/segmentation/MaskedVolume.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace lucent {

Volume maskedVolume(const Volume& volume, const SegmentMask& mask, MaskKeep keep) {
    if (mask.dims() != volume.dims()) {
        throw std::invalid_argument("masked volume: the segment lies on another grid than the "
                                    "volume");
    }
    Volume out(volume.geometry(), volume.type());
    static_cast<SeriesInfo&>(out) = static_cast<const SeriesInfo&>(volume);
    out.warnings = volume.warnings;
    const auto in = volume.bytes();
    std::memcpy(out.bytes().data(), in.data(), in.size());
    const bool keepInside = keep == MaskKeep::Inside;
    visitVoxels(out, [&](auto voxels) {
        if (voxels.empty()) {
            return;
        }
        const auto lowest = *std::min_element(voxels.begin(), voxels.end());
        const auto words = mask.words();
        for (std::size_t w = 0; w < words.size(); ++w) {
            // The bits of the voxels to clear in this word of 64.
            std::uint64_t clear = keepInside ? ~words[w] : words[w];
            const std::size_t base = w * 64;
            while (clear != 0) {
                const std::size_t at = base + std::size_t(std::countr_zero(clear));
                if (at >= voxels.size()) {
                    break;
                }
                voxels[at] = lowest;
                clear &= clear - 1;
            }
        }
    });
    return out;
}

} // namespace lucent
