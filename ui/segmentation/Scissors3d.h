#pragma once
// Scissors through the 3D view (the Segment Editor's Scissors effect in 3D): installed on a
// VolumeView as an event filter, a left-drag draws a freehand outline, a circle (from its
// centre) or a rectangle (corner to corner) over the rendering; the release cuts the segment
// along the view's rays (core/segmentation/ScissorsCut.h): erase or fill, inside or outside
// the shape, one undo step of the Segmentation. The other buttons and the wheel still move
// the camera; Escape drops a shape being drawn. While disabled the view is left alone.

#include <cstdint>
#include <memory>
#include <vector>

#include <QObject>
#include <QPointF>
#include <QPointer>

#include "core/segmentation/ScissorsCut.h"

namespace lucent {

class Segmentation;
class VolumeView;
class ScissorsOverlay;

class Scissors3d : public QObject {
    Q_OBJECT

public:
    enum class Shape { Freehand, Circle, Rectangle };

    // The segmentation must lie on the grid of the view's volume and outlive this object.
    Scissors3d(VolumeView* view, Segmentation* segmentation, std::uint32_t segment);
    ~Scissors3d() override;

    void setEnabled(bool enabled);
    bool enabled() const { return enabled_; }
    void setShape(Shape shape) { shape_ = shape; }
    Shape shape() const { return shape_; }
    void setOperation(ScissorsOperation operation) { operation_ = operation; }
    ScissorsOperation operation() const { return operation_; }
    void setSegment(std::uint32_t segment) { segment_ = segment; }
    std::uint32_t segment() const { return segment_; }

    // The shape being drawn, in view pixels (none: an empty polygon).
    ScreenShape currentShape() const;
    bool drawing() const { return drawing_; }

signals:
    // After a cut: the voxels of the segment it changed (0: nothing, no undo step made).
    void cut(std::size_t voxelsChanged);
    // Why a shape could not cut (no volume, another grid, a locked segment).
    void refused(const QString& reason);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    void finish();
    void cancel();

    QPointer<VolumeView> view_;
    const QObject* watched_; // the view, compared by address alone (no cast while it goes)
    QPointer<QObject> watchedObject_;
    Segmentation* segmentation_;
    std::uint32_t segment_;
    std::unique_ptr<ScissorsOverlay> overlay_;
    bool enabled_ = false;
    bool drawing_ = false;
    Shape shape_ = Shape::Freehand;
    ScissorsOperation operation_ = ScissorsOperation::EraseInside;
    std::vector<QPointF> points_; // freehand outline; first and last point for the others
};

} // namespace lucent
