#include "ui/fusion/ViewportFusion.h"

#include <glm/gtc/matrix_transform.hpp>

#include "core/fusion/OverlayResampler.h"
#include "core/mpr/PlaneSampler.h"
#include "ui/fusion/FusionNudge.h"
#include "ui/fusion/OverlayWindowDrag.h"
#include "ui/fusion/SliceFusion.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SliceView.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportLinks.h"
#include "ui/viewports/ViewportRegistration.h"
#include "ui/viewports/ViewportWorkspace.h"
#include "ui/volume/VolumeView.h"

namespace lucent {

namespace {

// What the overlay's values are in, for its colour bar.
// The unit of the overlay's values as loaded: HU, SUVbw (or a PET's stored unit when it
// could not be shown in SUV), else none.
QString overlayUnit(const Volume& overlay) {
    if (overlay.pet) {
        return QString::fromStdString(overlay.pet->unit());
    }
    return overlay.modality == "CT" ? QStringLiteral("HU") : QString();
}

} // namespace

std::optional<glm::dmat4> fusionTransform(const SeriesLink& link) {
    switch (link.kind) {
    case SeriesLink::Kind::SamePosition:
        return glm::dmat4(1.0);
    case SeriesLink::Kind::Registered:
        return link.transform;
    case SeriesLink::Kind::Offset:
        return glm::translate(glm::dmat4(1.0), link.offset);
    case SeriesLink::Kind::None:
        break;
    }
    return std::nullopt;
}

FusionStyle defaultFusionStyle(const Volume& base, const Volume& overlay) {
    FusionStyle style;
    const WindowLevel window = defaultWindow(overlay);
    style.center = window.center;
    style.width = window.width;
    if (overlay.modality == "PT") {
        style.colourMap = FusionColourMap::HotIron;
        style.opacity = 0.5;
        style.clearBelowWindow = true;
        // From no uptake up: the low end of the window at the overlay's smallest values.
        style.center = 0.5 * style.width + std::min(0.0, window.center - 0.5 * window.width);
    } else if (!base.modality.empty() && overlay.modality == base.modality) {
        style.colourMap = FusionColourMap::Grey;
        style.mode = FusionMode::Checkerboard;
    } else {
        style.colourMap = FusionColourMap::HotIron;
        style.opacity = 0.4;
    }
    return style;
}

ViewportFusion::ViewportFusion(ViewportWorkspace* workspace, QObject* parent)
    : QObject(parent), workspace_(workspace), nudge_(new FusionNudge(this)),
      windowDrag_(new OverlayWindowDrag(this)) {
    ViewportGrid* grid = workspace->grid();
    // A viewport that shows something else keeps its overlay while its series is the same.
    connect(grid, &ViewportGrid::viewportContentChanged, this, [this](Viewport* viewport) {
        const auto it = fused_.find(viewport);
        if (it == fused_.end()) {
            return;
        }
        if (viewport->session() != it->second.base || !apply(viewport, it->second, nullptr)) {
            fused_.erase(it);
        }
        emit fusionChanged(viewport);
    });
    connect(grid, &ViewportGrid::viewportsChanged, this, [this] {
        const std::vector<Viewport*> now = workspace_->grid()->viewports();
        std::erase_if(fused_, [&](const auto& entry) {
            return std::find(now.begin(), now.end(), entry.first) == now.end();
        });
    });
    // A registration changes the transform of pairs already fused.
    connect(workspace->registration(), &ViewportRegistration::finished, this,
            [this](bool ok, const QString&) {
                if (ok) {
                    reapplyAll();
                }
            });
}

bool ViewportFusion::fuse(Viewport* viewport, SeriesSession* overlay, QString* message) {
    if (viewport == nullptr || viewport->session() == nullptr || !viewport->session()->volume() ||
        viewport->sliceView() == nullptr) {
        if (message != nullptr) {
            *message = tr("Fusion needs an MPR viewport that shows a volume.");
        }
        return false;
    }
    if (overlay == nullptr || !overlay->volume()) {
        if (message != nullptr) {
            *message = tr("Only a volume can be fused over a viewport.");
        }
        return false;
    }
    Fused fused{viewport->session(), overlay,
                defaultFusionStyle(*viewport->session()->volume(), *overlay->volume())};
    if (fused.style.mode == FusionMode::Checkerboard) { // compare in the base's window
        fused.style.center = viewport->session()->cursor()->windowCenter();
        fused.style.width = viewport->session()->cursor()->windowWidth();
    }
    if (!apply(viewport, fused, message)) {
        return false;
    }
    fused_[viewport] = fused;
    emit fusionChanged(viewport);
    return true;
}

bool ViewportFusion::apply(Viewport* viewport, const Fused& fused, QString* message) {
    SliceView* view = viewport->sliceView();
    if ((view == nullptr && viewport->volumeView() == nullptr) || fused.base == nullptr ||
        fused.overlay == nullptr) {
        return false;
    }
    const SeriesLink link = workspace_->links()->linkBetween(*fused.base, *fused.overlay);
    const std::optional<glm::dmat4> transform = fusionTransform(link);
    if (!transform) {
        if (message != nullptr) {
            *message = tr("%1 cannot be fused over %2: %3. Register the two (Ctrl+Alt+R) or "
                          "link them (Link Here) first.")
                           .arg(fused.overlay->title(), fused.base->title(),
                                QString::fromStdString(link.reason));
        }
        return false;
    }
    if (view == nullptr) {
        applyTo3d(viewport, fused, *transform);
        return true;
    }
    FusionLayer layer;
    layer.overlay = fused.overlay->volume();
    layer.baseToOverlay = *transform;
    layer.style = fused.style;
    layer.title = fused.overlay->title();
    layer.unit = overlayUnit(*layer.overlay);
    view->setFusionLayer(std::move(layer));
    nudge_->watch(view);
    windowDrag_->watch(view);
    return true;
}

void ViewportFusion::applyTo3d(Viewport* viewport, const Fused& fused,
                               const glm::dmat4& transform) {
    const std::uint64_t job = ++lastJob_;
    jobs_[viewport] = job;
    if (workers_.size() > 8) {
        workers_.clear(); // joins the earlier jobs, done by now or nearly
    }
    const QPointer<Viewport> target(viewport);
    workers_.emplace_back([this, target, job, transform, base = fused.base->volume(),
                           overlay = fused.overlay->volume()] {
        auto onGrid =
            std::make_shared<const Volume>(resampleOverlay(*overlay, base->geometry(), transform));
        QMetaObject::invokeMethod(
            this,
            [this, target, job, onGrid] {
                const auto it = jobs_.find(target.data());
                const auto style = target ? styleOf(target) : std::nullopt;
                if (target && it != jobs_.end() && it->second == job && style &&
                    target->volumeView() != nullptr) {
                    target->volumeView()->setOverlay(onGrid, *style, overlayUnit(*onGrid));
                    emit overlayShownIn3d(target);
                }
            },
            Qt::QueuedConnection);
    });
}

void ViewportFusion::reapplyAll() {
    for (auto& [viewport, fused] : fused_) {
        apply(viewport, fused, nullptr);
    }
}

void ViewportFusion::setNudging(bool on) {
    nudging_ = on;
    for (auto& [viewport, fused] : fused_) {
        if (viewport->sliceView() != nullptr) {
            viewport->sliceView()->setCursor(on ? Qt::SizeAllCursor : Qt::ArrowCursor);
        }
    }
}

std::optional<glm::dmat4> ViewportFusion::transformOf(const Viewport* viewport) const {
    const auto it = fused_.find(viewport);
    if (it == fused_.end() || viewport->sliceView() == nullptr ||
        !viewport->sliceView()->fusion().active()) {
        return std::nullopt;
    }
    return viewport->sliceView()->fusion().layer()->baseToOverlay;
}

void ViewportFusion::previewTransform(Viewport* viewport, const glm::dmat4& transform) {
    if (viewport->sliceView() == nullptr || !viewport->sliceView()->fusion().active()) {
        return;
    }
    FusionLayer layer = *viewport->sliceView()->fusion().layer();
    layer.baseToOverlay = transform;
    viewport->sliceView()->setFusionLayer(std::move(layer));
}

void ViewportFusion::keepTransform(Viewport* viewport, const glm::dmat4& transform) {
    const auto it = fused_.find(viewport);
    if (it == fused_.end() || it->second.base == nullptr || it->second.overlay == nullptr) {
        return;
    }
    workspace_->links()->setTransform(it->second.base->info().seriesUid,
                                      it->second.overlay->info().seriesUid, transform);
    reapplyAll();
}

void ViewportFusion::clear(Viewport* viewport) {
    jobs_.erase(viewport);
    if (fused_.erase(viewport) > 0 && viewport->sliceView() != nullptr) {
        viewport->sliceView()->setFusionLayer(std::nullopt);
    }
    if (viewport->volumeView() != nullptr) {
        viewport->volumeView()->setOverlay(nullptr, {});
    }
    emit fusionChanged(viewport);
}

SeriesSession* ViewportFusion::overlayOf(const Viewport* viewport) const {
    const auto it = fused_.find(viewport);
    return it == fused_.end() ? nullptr : it->second.overlay.data();
}

std::optional<FusionStyle> ViewportFusion::styleOf(const Viewport* viewport) const {
    const auto it = fused_.find(viewport);
    if (it == fused_.end()) {
        return std::nullopt;
    }
    return it->second.style;
}

void ViewportFusion::setStyle(Viewport* viewport, const FusionStyle& style) {
    const auto it = fused_.find(viewport);
    if (it == fused_.end()) {
        return;
    }
    it->second.style = style;
    if (viewport->sliceView() != nullptr) {
        viewport->sliceView()->setFusionStyle(style);
    }
    if (viewport->volumeView() != nullptr) {
        viewport->volumeView()->setOverlayStyle(style);
    }
    emit fusionChanged(viewport);
}

} // namespace lucent
