#pragma once
// File > Export movie: a turntable of the 3D view (its camera, transfer
// function, mode and clip box) or a cine through the slices along i, j or k in
// the MPR views' window, written as MP4, WebM or GIF (core/movie) on a thread
// of its own with progress and cancel (BackgroundExportDialog). A cancelled or
// failed export leaves no file. Non-modal, like the DICOM export: the reader
// can go on reading.

#include <memory>

#include "core/mpr/PlaneSampler.h"
#include "core/scene/RenderDescription.h"
#include "ui/common/BackgroundExportDialog.h"

class QComboBox;
class QDoubleSpinBox;
class QLineEdit;
class QSpinBox;

namespace lucent {

class MovieExportDialog : public BackgroundExportDialog {
    Q_OBJECT

public:
    // `start`: the 3D view's description (its size is the dialog's default);
    // `window`: the MPR views' window, for cines.
    MovieExportDialog(std::shared_ptr<const Volume> volume, const RenderDescription& start,
                      const WindowLevel& window, QWidget* parent = nullptr);

    QComboBox* kind() const { return kind_; } // 0 turntable, 1 cine
    QSpinBox* frames() const { return frames_; }
    QDoubleSpinBox* degrees() const { return degrees_; }
    QComboBox* axis() const { return axis_; }
    QSpinBox* movieWidth() const { return width_; }
    QSpinBox* movieHeight() const { return height_; }
    QSpinBox* framesPerSecond() const { return fps_; }
    QLineEdit* output() const { return output_; }

private:
    void browse();
    void kindChanged();
    void start() override;

    std::shared_ptr<const Volume> volume_;
    RenderDescription start_;
    WindowLevel window_;
    QComboBox* kind_;
    QSpinBox* frames_;
    QDoubleSpinBox* degrees_;
    QComboBox* axis_;
    QSpinBox* width_;
    QSpinBox* height_;
    QSpinBox* fps_;
    QLineEdit* output_;
};

} // namespace lucent
