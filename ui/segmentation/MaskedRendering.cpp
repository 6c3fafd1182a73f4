#include "ui/segmentation/MaskedRendering.h"

#include <stdexcept>

#include "ui/volume/VolumeView.h"

namespace lucent {

MaskedRendering::MaskedRendering(VolumeView* view) : view_(view) {}

void MaskedRendering::swapVolume(std::shared_ptr<const Volume> volume) {
    // setVolume starts the view afresh (default camera and colours): what the user had set
    // goes back on.
    const Camera camera = view_->camera();
    const TransferFunction tf = view_->transferFunction();
    const RenderMode mode = view_->mode();
    const double iso = view_->isoValue();
    const ClipBox clip = view_->clipBox();
    const SamplingSettings sampling = view_->sampling();
    view_->setVolume(std::move(volume));
    view_->setTransferFunction(tf);
    view_->setMode(mode);
    view_->setIsoValue(iso);
    view_->setClipBox(clip);
    view_->setSampling(sampling);
    view_->setCamera(camera);
}

void MaskedRendering::show(const SegmentMask& mask, MaskKeep keep) {
    const std::shared_ptr<const Volume> source = original_ ? original_ : view_->volume();
    if (!source) {
        throw std::invalid_argument("masked rendering: the 3D view shows no volume");
    }
    auto masked = std::make_shared<const Volume>(maskedVolume(*source, mask, keep));
    original_ = source;
    swapVolume(std::move(masked));
}

void MaskedRendering::clear() {
    if (!original_) {
        return;
    }
    swapVolume(std::move(original_));
    original_.reset();
}

} // namespace lucent
