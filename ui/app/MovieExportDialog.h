#pragma once
// File > Export movie: a turntable of the 3D view (its camera, transfer
// function, mode and clip box) or a cine through the slices along i, j or k in
// the MPR views' window, written as MP4, WebM or GIF (core/movie) on a thread
// of its own with progress and cancel. A cancelled or failed export leaves no
// file. Non-modal, like the DICOM export: the reader can go on reading.

#include <QDialog>

#include <memory>
#include <thread>

#include "core/mpr/PlaneSampler.h"
#include "core/scene/RenderDescription.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QSpinBox;

namespace lucent {

class MovieExportDialog : public QDialog {
    Q_OBJECT

public:
    // `start`: the 3D view's description (its size is the dialog's default);
    // `window`: the MPR views' window, for cines.
    MovieExportDialog(std::shared_ptr<const Volume> volume, const RenderDescription& start,
                      const WindowLevel& window, QWidget* parent = nullptr);
    ~MovieExportDialog() override; // cancels a running export and waits for it

    QComboBox* kind() const { return kind_; } // 0 turntable, 1 cine
    QSpinBox* frames() const { return frames_; }
    QDoubleSpinBox* degrees() const { return degrees_; }
    QComboBox* axis() const { return axis_; }
    QSpinBox* movieWidth() const { return width_; }
    QSpinBox* movieHeight() const { return height_; }
    QSpinBox* framesPerSecond() const { return fps_; }
    QLineEdit* output() const { return output_; }
    QPushButton* exportButton() const { return export_; }
    // Cancel while exporting, Close otherwise.
    QPushButton* closeButton() const { return close_; }
    QLabel* status() const { return status_; }
    bool running() const { return running_; }

signals:
    void progressed(int done, int total);
    // ok is false after an error or a cancel; message says what was written or why not.
    void exportFinished(bool ok, const QString& message);

private:
    void browse();
    void kindChanged();
    void start();
    void done(bool ok, const QString& message);

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
    QProgressBar* bar_;
    QLabel* status_;
    QPushButton* export_;
    QPushButton* close_;
    bool running_ = false;
    std::jthread worker_;
};

} // namespace lucent
