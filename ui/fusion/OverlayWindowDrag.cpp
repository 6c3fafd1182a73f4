#include "ui/fusion/OverlayWindowDrag.h"

#include <algorithm>

#include <QMouseEvent>

#include "ui/fusion/ViewportFusion.h"
#include "ui/mpr/SliceView.h"
#include "ui/viewports/Viewport.h"

namespace lucent {

OverlayWindowDrag::OverlayWindowDrag(ViewportFusion* fusion) : QObject(fusion), fusion_(fusion) {}

void OverlayWindowDrag::watch(SliceView* view) {
    view->removeEventFilter(this);
    view->installEventFilter(this);
}

bool OverlayWindowDrag::eventFilter(QObject* watched, QEvent* event) {
    const auto type = event->type();
    if (type != QEvent::MouseButtonPress && type != QEvent::MouseMove &&
        type != QEvent::MouseButtonRelease) {
        return false;
    }
    const auto* mouse = static_cast<QMouseEvent*>(event);
    if (type == QEvent::MouseButtonPress) {
        Viewport* viewport = nullptr;
        for (QObject* o = watched; o != nullptr && viewport == nullptr; o = o->parent()) {
            viewport = qobject_cast<Viewport*>(o);
        }
        const auto style = viewport != nullptr ? fusion_->styleOf(viewport) : std::nullopt;
        if (!style || mouse->button() != Qt::RightButton ||
            !(mouse->modifiers() & Qt::AltModifier)) {
            return false;
        }
        drag_ = Drag{viewport, mouse->position().toPoint(), style->center, style->width};
        return true;
    }
    if (!drag_) {
        return false;
    }
    const auto style = fusion_->styleOf(drag_->viewport);
    if (style) {
        const QPoint d = mouse->position().toPoint() - drag_->start;
        const double step = drag_->width / 400.0;
        FusionStyle changed = *style;
        changed.center = drag_->center + d.y() * step;
        changed.width = std::max(drag_->width * 1e-3, drag_->width + d.x() * step);
        fusion_->setStyle(drag_->viewport, changed);
    }
    if (type == QEvent::MouseButtonRelease) {
        drag_.reset();
    }
    return true;
}

} // namespace lucent
