#pragma once
// The Segments dock's tools that act through a 3D view of the series, and grow from seeds:
// scissors through the rendering (shape and operation), the rendering masked by the active
// segment (alone, or cut away) and back, the segment's surface shown and exported (STL, PLY,
// OBJ), and "Grow from seeds". Added to the panel's "More" tab; the 3D view is whichever the
// window shows the active session's series in (viewFor).

#include <functional>
#include <memory>

#include <QPointer>
#include <QWidget>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QPushButton;

namespace lucent {

class GrowFromSeedsEffect;
class MaskedRendering;
class Scissors3d;
class SegmentationSession;
class SegmentsPanel;
class Volume;
class VolumeView;

class SegmentTools3d : public QWidget {
    Q_OBJECT

public:
    // The 3D view showing a series (nullptr when none does).
    using ViewFor = std::function<VolumeView*(const Volume& series)>;

    SegmentTools3d(SegmentsPanel* panel, ViewFor viewFor, QWidget* parent = nullptr);
    ~SegmentTools3d() override;

    QPushButton* scissorsButton() const { return scissorsOn_; }
    QComboBox* scissorsShape() const { return shape_; }
    QComboBox* scissorsOperation() const { return operation_; }
    Scissors3d* scissors() const; // while they are on
    GrowFromSeedsEffect* grow() const { return grow_; }
    QCheckBox* growAfterStrokes() const { return growAfterStrokes_; }

    // What the buttons do, on the panel's session and active segment; false, with a message,
    // when there is none, it is locked or empty, or no 3D view shows the series.
    bool setScissors(bool on);
    bool showMasked(bool segmentAlone);
    bool showWholeVolume();
    bool showSurface();
    bool exportSurface(const QString& file);
    bool growFromSeeds();

signals:
    void message(const QString& text, int timeoutMs);

private:
    QWidget* makeScissorsBox();
    QWidget* makeViewBox();
    QWidget* makeGrowBox();
    // The panel's session, its active segment and the 3D view of its series, or a message.
    VolumeView* viewOfActive(const QString& what, bool needVoxels);

    SegmentsPanel* panel_;
    ViewFor viewFor_;
    GrowFromSeedsEffect* grow_;
    QPointer<Scissors3d> scissors_; // a child of its view, which may go first
    QPointer<SegmentationSession> scissorsSession_;
    std::unique_ptr<MaskedRendering> masked_;
    QPointer<VolumeView> maskedView_;
    QPushButton* scissorsOn_ = nullptr;
    QComboBox* shape_ = nullptr;
    QComboBox* operation_ = nullptr;
    QDoubleSpinBox* growMargin_ = nullptr;
    QCheckBox* growAfterStrokes_ = nullptr;
};

} // namespace lucent
