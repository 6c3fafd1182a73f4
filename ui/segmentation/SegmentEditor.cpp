#include "ui/segmentation/SegmentEditor.h"

#include <algorithm>

#include "ui/mpr/SliceView.h"
#include "ui/segmentation/SegmentationSession.h"
#include "ui/segmentation/SliceSegments.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportWorkspace.h"

namespace lucent {

SegmentEditor::SegmentEditor(ViewportWorkspace* workspace, QObject* parent)
    : QObject(parent), workspace_(workspace), sessions_(new SegmentationSessions(this)) {
    ViewportGrid* grid = workspace_->grid();
    connect(grid, &ViewportGrid::viewportsChanged, this, &SegmentEditor::attachLayers);
    connect(grid, &ViewportGrid::viewportContentChanged, this, [this, grid](Viewport* viewport) {
        attachLayers();
        if (viewport == grid->activeViewport()) {
            emit activeSessionChanged(activeSession());
        }
    });
    connect(grid, &ViewportGrid::activeViewportChanged, this,
            [this] { emit activeSessionChanged(activeSession()); });
    connect(sessions_, &SegmentationSessions::sessionOpened, this,
            [this](SegmentationSession* session) {
                connect(session, &SegmentationSession::segmentsChanged, this,
                        &SegmentEditor::repaintLayers);
                connect(session, &SegmentationSession::previewChanged, this,
                        &SegmentEditor::repaintLayers);
            });
    attachLayers();
}

SegmentationSession* SegmentEditor::activeSession() const {
    const Viewport* active = workspace_->grid()->activeViewport();
    if (active == nullptr || active->session() == nullptr) {
        return nullptr;
    }
    return sessions_->sessionFor(active->session()->volume());
}

void SegmentEditor::attachLayers() {
    std::erase_if(layers_, [](const auto& entry) { return entry.second.isNull(); });
    for (Viewport* viewport : workspace_->grid()->viewports()) {
        SliceView* view = viewport->sliceView();
        if (view != nullptr && !layers_.contains(view)) {
            layers_[view] = new SliceSegments(this, view); // a child of the view
        }
    }
}

void SegmentEditor::repaintLayers() {
    for (const auto& [view, layer] : layers_) {
        if (layer) {
            layer->update();
        }
    }
}

SegmentEditor::~SegmentEditor() {
    for (const auto& [view, layer] : layers_) {
        delete layer.data(); // null when its view went first
    }
}

SliceSegments* SegmentEditor::layerOf(const SliceView* view) const {
    const auto it = layers_.find(view);
    return it == layers_.end() ? nullptr : it->second.data();
}

void SegmentEditor::setTool(SegmentTool tool) {
    if (tool == tool_) {
        return;
    }
    tool_ = tool;
    for (const auto& [view, layer] : layers_) {
        if (layer) {
            layer->cancel();
        }
    }
    emit toolChanged(tool);
}

void SegmentEditor::setBrushRadiusMm(double mm) {
    brushRadiusMm_ = std::max(0.1, mm);
    emit brushChanged();
    repaintLayers();
}

void SegmentEditor::setBrushSphere(bool sphere) {
    brushSphere_ = sphere;
    emit brushChanged();
}

void SegmentEditor::setDisplay(const SegmentDisplay& display) {
    display_ = display;
    repaintLayers();
}

void SegmentEditor::say(const QString& text) {
    message_ = text;
    emit message(text, 6000);
}

bool SegmentEditor::applyToActive(const QString& what, const Effect& effect,
                                  const std::string& algorithm) {
    SegmentationSession* session = activeSession();
    if (session == nullptr) {
        say(tr("%1: the active viewport shows no volume").arg(what));
        return false;
    }
    const Segment* segment = session->active();
    if (segment == nullptr) {
        say(tr("%1: add or choose a segment first").arg(what));
        return false;
    }
    if (segment->locked) {
        say(tr("%1: %2 is locked").arg(what, QString::fromStdString(segment->name)));
        return false;
    }
    const std::uint32_t id = segment->id;
    SegmentMask result = effect(*segment->mask, *session);
    if (result == *session->segmentation().find(id)->mask) {
        say(tr("%1 changed nothing").arg(what));
        return false;
    }
    session->apply(id, std::move(result), what, algorithm);
    say(what);
    return true;
}

} // namespace lucent
