#pragma once

#include <array>
#include <map>
#include <memory>
#include <string>

#include <QWidget>

#include "core/quality/MeasuredFront.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QSlider;
class QSpinBox;
class QThread;

namespace lucent {

class VolumeView;

// A small panel for the 3D view: transfer-function preset, render mode (with the
// iso value for isosurfaces; it follows the view's mode), quality, a camera reset, the
// rotating MIP (the view's RotatingMip action), and the clip box as two sliders per
// volume axis (first and last voxel index kept on i, j and k).
//
// Quality: Manual leaves the view's sampling alone; Fast, Balanced, Best (time
// budgets, see core/raycast/QualityChoice.h) and Target (a time per frame)
// choose the still frames' sampling from the quick front of the volume on the
// view's backend, and a coarser step of the same filter while dragging. The
// front is measured once per volume, backend and renderer version in a
// background thread and kept in the cache dir.
class VolumeViewControls : public QWidget {
    Q_OBJECT

public:
    explicit VolumeViewControls(VolumeView* view, QWidget* parent = nullptr);

    QComboBox* presetPicker() const { return presets_; }
    QComboBox* modePicker() const { return modes_; }
    // axis 0..2 (i, j, k); end 0: first voxel kept, 1: last voxel kept.
    QSlider* clipSlider(int axis, int end) const;
    // Manual, Fast, Balanced, Best, Target.
    QComboBox* qualityPicker() const { return quality_; }
    QSpinBox* qualityTarget() const { return targetMs_; }
    // What was chosen, or that the front is being measured.
    QString qualityStatus() const;
    // Where fronts are kept (default: QStandardPaths::CacheLocation).
    void setQualityCacheDir(const QString& dir);
    QString qualityCacheDir() const { return cacheDir_; }
    // What the view was last given for dragging (default while Manual).
    const InteractiveQuality& dragQuality() const { return drag_; }

    ~VolumeViewControls() override;

Q_SIGNALS:
    // The view's sampling now follows a choice from a measured front.
    void qualityChosen(const QString& status);

protected:
    // The view's size sets the predicted times: a resize chooses again.
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    struct Measurement;

    void volumeChanged();
    void applyClip();
    void updateQuality();
    void applyFront(const MeasuredFront& front);
    void startMeasuring(const RenderDescription& description, const std::string& backend);
    void measuringFinished();
    void setQualityStatus(const QString& text);

    VolumeView* view_;
    QComboBox* presets_ = nullptr;
    QComboBox* modes_ = nullptr;
    QDoubleSpinBox* iso_ = nullptr;
    std::array<QSlider*, 6> clip_{};

    QComboBox* quality_ = nullptr;
    QSpinBox* targetMs_ = nullptr;
    QLabel* qualityStatus_ = nullptr;
    QString cacheDir_;
    std::map<std::string, MeasuredFront> fronts_; // by frontKey(), this session
    SamplingSettings manualSampling_;             // the view's own, for Manual
    bool chosenByQuality_ = false;
    InteractiveQuality drag_;
    std::shared_ptr<Measurement> measuring_;
    std::unique_ptr<QThread> thread_;
};

} // namespace lucent
