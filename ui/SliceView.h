#pragma once

#include <memory>
#include <vector>

#include <QImage>
#include <QPoint>
#include <QWidget>

#include "core/mpr/PlaneSampler.h"
#include "core/volume/Volume.h"

class QPainter;

namespace lucent {

class MprCursor;

// One MPR view: the plane of its orientation through the shared crosshair point,
// the volume fitted to the widget. Wheel: one slice along the plane normal
// (forward goes deeper, i.e. along the viewing direction). Right-drag: window
// (right = wider) and level (down = higher), cursor->windowStep() units per pixel.
// Left-click or left-drag: moves the crosshair point, and with it the other views.
class SliceView : public QWidget {
    Q_OBJECT

public:
    SliceView(Orientation orientation, MprCursor* cursor, QWidget* parent = nullptr);

    void setVolume(std::shared_ptr<const Volume> volume);
    const std::shared_ptr<const Volume>& volume() const { return volume_; }
    Orientation orientation() const { return orientation_; }

    // The plane shown now: through the crosshair point, centred on the volume, one
    // plane pixel per widget pixel (pixel (x, y) at widget position (x, y)).
    SlicePlane plane() const;
    // How far one wheel notch moves the plane, mm.
    double sliceStep() const;
    // The plane's position along the patient axis closest to its normal, mm (x, y or z).
    double slicePosition() const;
    // The grey image of the current plane and window, as painted under the overlays.
    QImage image();

    QSize sizeHint() const override { return {400, 400}; }
    QSize minimumSizeHint() const override { return {120, 120}; }

protected:
    void paintEvent(QPaintEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;

private:
    // The normal flipped so that its strongest patient component is positive.
    glm::dvec3 positiveNormal() const;
    void moveSlices(double slices);
    void setCrosshair(const QPointF& pos);
    void paintOverlay(QPainter& painter, const SlicePlane& plane);

    Orientation orientation_;
    MprCursor* cursor_;
    std::shared_ptr<const Volume> volume_;

    std::vector<float> samples_;
    SlicePlane sampledPlane_;
    bool samplesValid_ = false;
    QImage image_;
    double imageCenter_ = 0.0;
    double imageWidth_ = 0.0;
    bool imageValid_ = false;

    enum class Drag { None, Crosshair, Window };
    Drag drag_ = Drag::None;
    QPoint dragStart_;
    double dragCenter_ = 0.0;
    double dragWidth_ = 0.0;
    int wheelRemainder_ = 0;
};

} // namespace lucent
