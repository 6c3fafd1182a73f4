#pragma once
// The volume rendering masked by a segment, as the Segment Editor's "Mask volume" effect: a
// copy of the volume with the voxels outside the segment (or, to cut it away, inside it) set
// to the volume's minimum, given to the 3D view instead of the volume. The table cut away,
// a bone removed.

#include "core/segmentation/SegmentMask.h"
#include "core/volume/Volume.h"

namespace lucent {

enum class MaskKeep {
    Inside, // the segment alone is shown
    Outside // the segment is cut away
};

// A copy of `volume` (same type, geometry and series description) with the voxels not kept
// set to its smallest value. std::invalid_argument for a mask on another grid.
Volume maskedVolume(const Volume& volume, const SegmentMask& mask, MaskKeep keep);

} // namespace lucent
