// VolumeView: a fused overlay drawn with the volume (the renderers' RenderOverlay).
#include "ui/volume/VolumeView.h"

namespace lucent {

void VolumeView::setOverlay(std::shared_ptr<const Volume> onGrid, const FusionStyle& style,
                            const QString& unit) {
    if (onGrid && volume_ && onGrid->dims() != volume_->dims()) {
        onGrid.reset(); // not on this volume's grid (the volume changed meanwhile)
    }
    overlay_ = std::move(onGrid);
    overlayStyle_ = style;
    overlayUnit_ = unit;
    requestRender();
}

void VolumeView::setOverlayStyle(const FusionStyle& style) {
    overlayStyle_ = style;
    if (overlay_) {
        requestRender();
    }
}

} // namespace lucent
