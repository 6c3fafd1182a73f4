#pragma once
// The 3D view's rendering masked by a segment (core/segmentation/MaskedVolume.h): the view is
// given a masked copy of its volume, the segment alone or the segment cut away (the table,
// a bone), and its own volume back on clear(). The camera, transfer function, mode, iso
// value, clip box and sampling stay as they were across both switches; a fused overlay is
// dropped (it is shown on the volume it was resampled to).

#include <memory>

#include "core/segmentation/MaskedVolume.h"

namespace lucent {

class VolumeView;

class MaskedRendering {
public:
    explicit MaskedRendering(VolumeView* view);

    // Masks the view's volume (the original one while a mask is shown) by `mask`.
    // std::invalid_argument for a mask on another grid or a view with no volume.
    void show(const SegmentMask& mask, MaskKeep keep);
    // The original volume back (nothing when no mask is shown).
    void clear();
    bool active() const { return original_ != nullptr; }
    const std::shared_ptr<const Volume>& original() const { return original_; }

private:
    void swapVolume(std::shared_ptr<const Volume> volume);

    VolumeView* view_;
    std::shared_ptr<const Volume> original_; // while masked
};

} // namespace lucent
