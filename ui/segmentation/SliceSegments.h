#pragma once
// The segments over one MPR view of the grid: each visible segment's voxels on the view's
// plane (the nearest voxel of each pixel, so oblique planes too) as a semi-transparent fill
// and/or outline in its colour, a preview in place of its segment, the brush under the
// cursor and the outline being drawn. A transparent child of the SliceView that also takes
// the view's left button while a Segment Editor tool is on (an event filter), so the view
// itself knows nothing of segments.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <QImage>
#include <QPointF>
#include <QWidget>

#include "core/mpr/PlaneSampler.h"
#include "core/segmentation/SegmentBrush.h"
#include "core/segmentation/SegmentMask.h"

namespace lucent {

class SegmentEditor;
class SegmentationSession;
class SliceView;

class SliceSegments : public QWidget {
    Q_OBJECT

public:
    SliceSegments(SegmentEditor* editor, SliceView* view);

    // The overlay as painted last (the view's logical pixels, transparent where no segment
    // is drawn): for tests.
    const QImage& lastOverlay() const { return overlay_; }
    // The outline being drawn (patient mm).
    const std::vector<glm::dvec3>& outline() const { return outline_; }
    // Drops a stroke or an outline in progress.
    void cancel();

protected:
    void paintEvent(QPaintEvent* event) override;
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    struct Stroke {
        SegmentationSession* session = nullptr;
        std::uint32_t segment = 0;
        std::shared_ptr<SegmentMask> mask;
        glm::dvec3 last{0.0};
        bool erase = false;
        std::optional<SliceSlab> slab;
    };
    // The session of the view's series (made when `make`), nullptr without a volume.
    SegmentationSession* session(bool make) const;
    // The active segment to edit, after making the viewport active; nullptr (and a message)
    // when there is none or it is locked. Adds "Segment 1" to a series with none.
    SegmentationSession* editable();
    SliceSlab slabOfView() const;
    bool mousePress(const QPointF& pos);
    void mouseDrag(const QPointF& pos);
    void mouseRelease(const QPointF& pos);
    void brushTo(const glm::dvec3& point);
    void finishOutline();
    void renderOverlay(const SegmentationSession& session, const SlicePlane& plane);
    void paintDecorations(QPainter& painter, const SlicePlane& plane);

    SegmentEditor* editor_;
    SliceView* view_;
    std::optional<Stroke> stroke_;
    std::vector<glm::dvec3> outline_;
    bool outlineDragged_ = false;
    bool leftDown_ = false; // a press this layer took, not yet released
    std::optional<QPointF> hover_;
    QImage overlay_;
    // The voxel index of each pixel of the plane last painted (-1 outside the volume).
    std::vector<std::int64_t> voxelOfPixel_;
    SlicePlane indexedPlane_;
    glm::ivec3 indexedDims_{0};
};

} // namespace lucent
