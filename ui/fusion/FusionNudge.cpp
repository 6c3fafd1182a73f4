#include "ui/fusion/FusionNudge.h"

#include <cmath>
#include <numbers>

#include <QKeyEvent>
#include <QMouseEvent>

#include "core/fusion/OverlayNudge.h"
#include "ui/fusion/ViewportFusion.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SliceView.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"

namespace lucent {
namespace {

Viewport* viewportOf(QObject* object) {
    for (QObject* o = object; o != nullptr; o = o->parent()) {
        if (auto* viewport = qobject_cast<Viewport*>(o)) {
            return viewport;
        }
    }
    return nullptr;
}

constexpr double kDegree = std::numbers::pi / 180.0;

} // namespace

FusionNudge::FusionNudge(ViewportFusion* fusion) : QObject(fusion), fusion_(fusion) {}

void FusionNudge::watch(SliceView* view) {
    view->removeEventFilter(this);
    view->installEventFilter(this);
}

bool FusionNudge::eventFilter(QObject* watched, QEvent* event) {
    auto* view = qobject_cast<SliceView*>(watched);
    Viewport* viewport = viewportOf(watched);
    if (view == nullptr || viewport == nullptr || !fusion_->nudging() ||
        !fusion_->transformOf(viewport)) {
        return false;
    }
    switch (event->type()) {
    case QEvent::MouseButtonPress: {
        const auto* mouse = static_cast<QMouseEvent*>(event);
        return mouse->button() == Qt::LeftButton &&
               press(viewport, view, mouse->position().toPoint(),
                     mouse->modifiers() & Qt::ShiftModifier);
    }
    case QEvent::MouseMove:
    case QEvent::MouseButtonRelease:
        if (!drag_ || drag_->viewport != viewport) {
            return false;
        }
        drag(view, static_cast<QMouseEvent*>(event)->position().toPoint(),
             event->type() == QEvent::MouseButtonRelease);
        return true;
    case QEvent::KeyPress: {
        const auto* keyEvent = static_cast<QKeyEvent*>(event);
        return key(viewport, view, keyEvent->key(), keyEvent->modifiers() & Qt::ControlModifier);
    }
    default:
        return false;
    }
}

bool FusionNudge::press(Viewport* viewport, SliceView*, const QPoint& pos, bool turn) {
    drag_ = Drag{viewport, pos, *fusion_->transformOf(viewport), turn};
    return true;
}

void FusionNudge::drag(SliceView* view, const QPoint& pos, bool finished) {
    const SlicePlane plane = view->plane();
    glm::dmat4 nudged;
    if (drag_->turn) {
        // About the crosshair, where the reader looks.
        const glm::dvec3 pivot = drag_->viewport->session()->cursor()->point();
        const glm::dvec2 c = plane.pixelOf(pivot);
        const double before = std::atan2(drag_->start.y() - c.y, drag_->start.x() - c.x);
        const double now = std::atan2(pos.y() - c.y, pos.x() - c.x);
        // Screen angles grow from u towards v: a right-handed turn about u x v.
        nudged =
            nudgedTransform(drag_->transform, glm::dvec3(0.0), now - before, plane.normal(), pivot);
    } else {
        const QPoint d = pos - drag_->start;
        const glm::dvec3 shift =
            (plane.u * double(d.x()) + plane.v * double(d.y())) * plane.pixelSize;
        nudged = nudgedTransform(drag_->transform, shift);
    }
    if (finished) {
        fusion_->keepTransform(drag_->viewport, nudged);
        drag_.reset();
    } else {
        fusion_->previewTransform(drag_->viewport, nudged);
    }
}

bool FusionNudge::key(Viewport* viewport, SliceView* view, int key, bool ctrl) {
    const SlicePlane plane = view->plane();
    const glm::dmat4 now = *fusion_->transformOf(viewport);
    glm::dvec3 shift(0.0);
    double angle = 0.0;
    switch (key) {
    case Qt::Key_Left:
        (ctrl ? angle : shift.x) = -1.0;
        break;
    case Qt::Key_Right:
        (ctrl ? angle : shift.x) = 1.0;
        break;
    case Qt::Key_Up:
        shift.y = -1.0;
        break;
    case Qt::Key_Down:
        shift.y = 1.0;
        break;
    default:
        return false;
    }
    const glm::dvec3 mm = plane.u * shift.x + plane.v * shift.y;
    fusion_->keepTransform(viewport, nudgedTransform(now, mm, angle * kDegree, plane.normal(),
                                                     viewport->session()->cursor()->point()));
    return true;
}

} // namespace lucent
