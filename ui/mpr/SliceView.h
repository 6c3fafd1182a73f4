#pragma once

#include <memory>
#include <vector>

#include <QImage>
#include <QPoint>
#include <QWidget>

#include "core/mpr/PlaneSampler.h"
#include "core/volume/Volume.h"
#include "ui/fusion/SliceFusion.h"
#include "ui/mpr/ReferenceLines.h"
#include "ui/mpr/SliceMeasurements.h"
#include "ui/mpr/SliceTools.h"

class QMenu;
class QPainter;
class QTimer;

namespace lucent {

class MprCursor;

// One MPR view: the plane of its orientation (turned by the cursor's rotation for
// oblique planes) through the shared crosshair point, the volume fitted to the widget
// at zoom 1.
// Mouse: wheel = one slice along the plane normal (forward goes deeper); ctrl+wheel =
// zoom by zoomStepFactor() per notch about the mouse; right-drag = window (right =
// wider) and level (down = higher), cursor->windowStep() units per pixel; a right-click
// without a drag opens the context menu; middle-drag = pan; left-click/drag = crosshair
// (or the measurement tool; a press on a measurement's point handle drags it, whatever
// the tool); shift+left-drag = rotates the other two planes about this plane's normal.
// Keys: 1-8 window presets (brain, subdural, stroke, lung, mediastinum, abdomen, liver,
// bone) for all linked views; S = slab mode (thin, MIP, MinIP, average); [ and ] = slab
// thickness; the tools' keys (sliceTools(): D distance, A angle, K Cobb, T arrow,
// B bidirectional, E ellipse, P curved path: clicks add points, a double-click or Enter
// ends the path; Esc crosshair); Delete = delete the selected measurement; C = cine
// on/off; R = reset zoom and pan; O = reset obliquity; Menu = the context menu
// (sliceViewKeys() lists them for the shortcuts dialog).
// The measurements are the series' (SeriesMeasurements, shared with the other views
// and the list); without one set, the measuring tools do nothing.
class SliceView : public QWidget {
    Q_OBJECT

public:
    using Tool = SliceTool;

    SliceView(Orientation orientation, MprCursor* cursor, QWidget* parent = nullptr);

    void setVolume(std::shared_ptr<const Volume> volume);
    const std::shared_ptr<const Volume>& volume() const { return volume_; }
    Orientation orientation() const { return orientation_; }

    // The plane shown now: through the crosshair point, centred on the volume (plus the
    // pan), the volume fitted at zoom 1, pixel (x, y) at widget position (x, y).
    SlicePlane plane() const;
    // How far one wheel notch moves the plane, mm.
    double sliceStep() const;
    // The plane's position along the patient axis closest to its normal, mm (x, y or z).
    double slicePosition() const;
    // The grey image of the current plane and window, as painted under the overlays:
    // sampled at device pixels (devicePlane), its devicePixelRatio the widget's.
    QImage image();
    // The resliced value (HU for CT) of the device pixel at a widget position; NaN
    // outside the volume.
    double valueAt(const QPointF& pos);

    // A second series fused over this one (ui/fusion); nullopt: none.
    void setFusionLayer(std::optional<FusionLayer> layer);
    void setFusionStyle(const FusionStyle& style);
    const SliceFusion& fusion() const { return fusion_; }
    // The image as painted: image() with the fused overlay, if any.
    QImage fusedImage();
    // The overlay's value at a widget position (NaN without one or outside it).
    double overlayValueAt(const QPointF& pos);

    // Zoom: 1 fits the volume; each ctrl+wheel notch multiplies it by zoomStepFactor().
    double zoom() const { return zoom_; }
    static double zoomStepFactor() { return 1.25; }
    // Sets the zoom keeping the plane point under `anchor` (widget pixels) in place.
    void setZoom(double zoom, const QPointF& anchor);
    // The pan: how far the image centre moved from the volume's, mm along u and v.
    glm::dvec2 pan() const { return pan_; }
    void setPan(const glm::dvec2& pan);
    void resetZoomAndPan();
    // Zoom and pan together (a linked view takes both from another).
    void setZoomAndPan(double zoom, const glm::dvec2& pan);

    // Planes of other viewports (in this view's patient coordinates) drawn where they
    // cut this plane: the reference lines of a viewport grid.
    void setReferencePlanes(std::vector<ReferencePlane> planes);
    const std::vector<ReferencePlane>& referencePlanes() const { return references_; }

    // Thick slab along the plane normal; a thickness of 0 is a thin slice.
    double slabThickness() const { return slabThickness_; }
    SlabMode slabMode() const { return slabMode_; }
    void setSlab(double thicknessMm, SlabMode mode);

    void applyWindowPreset(int index); // into windowPresets(); all linked views follow

    Tool tool() const { return tool_; }
    void setTool(Tool tool);
    // The series' measurements this view draws and edits (not owned); nullptr: none.
    void setMeasurements(SeriesMeasurements* measurements);
    SeriesMeasurements* measurements() const { return measure_.document(); }
    // The drawing and editing on this view (the arrow's text editor, for one).
    const SliceMeasurements& measurementTools() const { return measure_; }
    void deleteSelectedMeasurement();
    void clearMeasurements();
    // How far from this plane a measurement may lie and still be drawn here, mm.
    double measurementTolerance() const;
    // The points of the curved path being clicked (patient mm); finishPath()
    // hands two or more on as curvedPathDrawn and goes back to the crosshair.
    const std::vector<glm::dvec3>& pathPoints() const { return path_; }
    void finishPath();

    bool cineRunning() const;
    void setCineRunning(bool running);
    int cineIntervalMs() const;

    // The view's actions (presets, slab, tools, cine, resets), as the context menu shows them.
    void fillContextMenu(QMenu& menu);

    QSize sizeHint() const override { return {400, 400}; }
    QSize minimumSizeHint() const override { return {120, 120}; }

signals:
    void toolChanged(lucent::SliceTool tool);
    // The zoom or the pan changed (by the user or a setter).
    void zoomPanChanged();
    // A curved path clicked on this view, and the view's normal (the up of a
    // stretched reformation: the path is seen as it was drawn).
    void curvedPathDrawn(const std::vector<glm::dvec3>& points, const glm::dvec3& viewNormal);

protected:
    void paintEvent(QPaintEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void mouseDoubleClickEvent(QMouseEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;

private:
    // The normal flipped so that its strongest patient component is positive.
    glm::dvec3 positiveNormal() const;
    // Moves by whole slices; returns whether the plane moved (it stops at the volume's end).
    bool moveSlices(double slices);
    void setCrosshair(const QPointF& pos);
    void rotateOthers(const QPointF& pos);
    void nextCineFrame();
    void cycleSlabMode();
    void changeSlabThickness(int steps);
    void showContextMenu(const QPoint& globalPos);
    QString sliceText() const;

    Orientation orientation_;
    MprCursor* cursor_;
    std::shared_ptr<const Volume> volume_;

    std::vector<float> samples_;
    SlicePlane sampledPlane_;
    bool samplesValid_ = false;
    QImage image_;
    double imageCenter_ = 0.0;
    double imageWidth_ = 0.0;
    bool imageInverted_ = false;
    bool imageValid_ = false;
    SliceFusion fusion_;

    double zoom_ = 1.0;
    glm::dvec2 pan_{0.0};
    double slabThickness_ = 0.0;
    double lastSlabThickness_ = 10.0;
    SlabMode slabMode_ = SlabMode::Mip;
    Tool tool_ = Tool::Crosshair;
    SliceMeasurements measure_{this};
    std::vector<glm::dvec3> path_;
    std::vector<ReferencePlane> references_;
    QTimer* cine_;

    enum class Drag { None, Crosshair, Window, Pan, Rotate, Measure };
    Drag drag_ = Drag::None;
    QPoint dragStart_;
    double dragCenter_ = 0.0;
    double dragWidth_ = 0.0;
    glm::dvec2 dragPan_{0.0};
    double dragAngle_ = 0.0;
    std::array<glm::dmat3, 3> dragRotations_{};
    int wheelRemainder_ = 0;
};

} // namespace lucent
