#pragma once
// Segments as one label volume (NIfTI labelmaps, what nnU-Net and most AI tools exchange)
// and back.

#include <string>
#include <vector>

#include "core/segmentation/Segmentation.h"
#include "core/volume/Volume.h"

namespace lucent {

// A UInt16 volume on the segmentation's grid: 0 for no segment, n for the n-th segment
// (1-based, in the list's order); where segments overlap, the later one's label is kept.
Volume labelmapOf(const Segmentation& segmentation);

// One segment per distinct non-zero value of `labels` (whole numbers, any voxel type), in
// increasing order, named "Label n" (or names[n-1] when given), each voxel exactly where
// its value is. One undo step each. Throws std::invalid_argument when the labels' grid
// differs from the segmentation's (dims) or a value is not a whole number.
std::vector<std::uint32_t> importLabelmap(Segmentation& segmentation, const Volume& labels,
                                          const std::vector<std::string>& names = {});

} // namespace lucent
