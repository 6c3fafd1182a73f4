#pragma once

#include <array>

#include <QWidget>

class QComboBox;
class QDoubleSpinBox;
class QSlider;

namespace lucent {

class VolumeView;

// A small panel for the 3D view: transfer-function preset, render mode (with the
// iso value for isosurfaces), a camera reset, and the clip box as two sliders per
// volume axis (first and last voxel index kept on i, j and k).
class VolumeViewControls : public QWidget {
    Q_OBJECT

public:
    explicit VolumeViewControls(VolumeView* view, QWidget* parent = nullptr);

    QComboBox* presetPicker() const { return presets_; }
    QComboBox* modePicker() const { return modes_; }
    // axis 0..2 (i, j, k); end 0: first voxel kept, 1: last voxel kept.
    QSlider* clipSlider(int axis, int end) const;

private:
    void volumeChanged();
    void applyClip();

    VolumeView* view_;
    QComboBox* presets_ = nullptr;
    QComboBox* modes_ = nullptr;
    QDoubleSpinBox* iso_ = nullptr;
    std::array<QSlider*, 6> clip_{};
};

} // namespace lucent
