#include "core/segmentation/Labelmap.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace lucent {

Volume labelmapOf(const Segmentation& segmentation) {
    Volume labels(segmentation.geometry(), VoxelType::UInt16);
    const std::span<std::uint16_t> out = labels.voxels<std::uint16_t>();
    std::fill(out.begin(), out.end(), std::uint16_t{0}); // a new Volume is not cleared
    std::uint16_t label = 0;
    for (const Segment& s : segmentation.segments()) {
        ++label;
        s.mask->forEachSet([&](std::size_t i) { out[i] = label; });
    }
    return labels;
}

std::vector<std::uint32_t> importLabelmap(Segmentation& segmentation, const Volume& labels,
                                          const std::vector<std::string>& names) {
    if (labels.dims() != segmentation.geometry().dims) {
        throw std::invalid_argument("the labelmap's grid differs from the series'");
    }
    std::map<long, SegmentMask> masks;
    visitVoxels(labels, [&](auto voxels) {
        for (std::size_t i = 0; i < voxels.size(); ++i) {
            const double v = static_cast<double>(voxels[i]);
            if (v == 0.0) {
                continue;
            }
            if (v != std::floor(v)) {
                throw std::invalid_argument("the labelmap holds " + std::to_string(v) +
                                            ", not a whole number");
            }
            auto [it, added] = masks.try_emplace(static_cast<long>(v), labels.dims());
            it->second.set(i);
        }
    });
    std::vector<std::uint32_t> ids;
    for (auto& [value, mask] : masks) {
        const std::string name = value >= 1 && std::size_t(value) <= names.size()
                                     ? names[std::size_t(value) - 1]
                                     : "Label " + std::to_string(value);
        const std::uint32_t id = segmentation.add(name);
        segmentation.setMask(id, std::move(mask), "Import " + name);
        ids.push_back(id);
    }
    return ids;
}

} // namespace lucent
