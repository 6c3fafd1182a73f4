#pragma once
// The Segment Editor's state across the viewport grid: the segments of each series
// (SegmentationSessions), the tool the MPR views' left button uses (paint, erase, draw,
// the island clicked), the brush, how segments are drawn, and the non-interactive effects
// run on the active segment. Every MPR view of the grid gets a SliceSegments layer.

#include <functional>
#include <map>
#include <string>

#include <QObject>
#include <QPointer>
#include <QString>

#include "core/segmentation/SegmentMask.h"

namespace lucent {

class SegmentationSession;
class SegmentationSessions;
class SliceSegments;
class SliceView;
class ViewportWorkspace;

enum class SegmentTool { None, Paint, Erase, Draw, PickIsland };

// How the views draw segments: a semi-transparent fill and/or the outline, in its colour.
struct SegmentDisplay {
    bool fill = true;
    bool outline = true;
    double fillOpacity = 0.4;
};

class SegmentEditor : public QObject {
    Q_OBJECT

public:
    explicit SegmentEditor(ViewportWorkspace* workspace, QObject* parent = nullptr);

    ViewportWorkspace* workspace() const { return workspace_; }
    SegmentationSessions* sessions() const { return sessions_; }
    // The session of the active viewport's series (made on first use); nullptr when it
    // shows no volume.
    SegmentationSession* activeSession() const;

    SegmentTool tool() const { return tool_; }
    void setTool(SegmentTool tool);
    // The brush: its radius (mm), and a sphere (reaching the slices above and below) or
    // its disc on the view's slice alone.
    double brushRadiusMm() const { return brushRadiusMm_; }
    void setBrushRadiusMm(double mm);
    bool brushSphere() const { return brushSphere_; }
    void setBrushSphere(bool sphere);
    const SegmentDisplay& display() const { return display_; }
    void setDisplay(const SegmentDisplay& display);

    // Replaces the active segment's voxels by effect(its voxels, the session): one undo
    // step named `what`. False, with the reason in lastMessage() and message(), without a
    // series, a segment, or when it is locked.
    using Effect = std::function<SegmentMask(const SegmentMask&, const SegmentationSession&)>;
    bool applyToActive(const QString& what, const Effect& effect,
                       const std::string& algorithm = {});

    // The layer drawn over an MPR view of the grid (nullptr for another view).
    SliceSegments* layerOf(const SliceView* view) const;
    // The layers go with the editor: they ask it for the tool at every event of their view.
    ~SegmentEditor() override;
    const QString& lastMessage() const { return message_; }
    void say(const QString& text);

signals:
    // The active viewport shows another series (or none): the panel follows.
    void activeSessionChanged(lucent::SegmentationSession* session);
    void toolChanged(lucent::SegmentTool tool);
    void brushChanged();
    void message(const QString& text, int timeoutMs);

private:
    void attachLayers();
    void repaintLayers();

    ViewportWorkspace* workspace_;
    SegmentationSessions* sessions_;
    std::map<const SliceView*, QPointer<SliceSegments>> layers_;
    SegmentTool tool_ = SegmentTool::None;
    double brushRadiusMm_ = 5.0;
    bool brushSphere_ = true;
    SegmentDisplay display_;
    QString message_;
};

} // namespace lucent
