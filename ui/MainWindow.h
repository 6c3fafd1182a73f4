#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>

#include <QMainWindow>
#include <QPointer>

#include "core/io/LoadControl.h"
#include "core/mpr/PlaneSampler.h"
#include "core/volume/Volume.h"

class QLabel;
class QProgressDialog;

namespace lucent {

class MprCursor;
class SliceView;
class TransferFunctionEditor;
class VolumeView;

// The workstation window: axial, coronal and sagittal views side by side, linked
// through one crosshair and window, and a status bar describing the volume.
class MainWindow : public QMainWindow {
    Q_OBJECT

public:
    explicit MainWindow(QWidget* parent = nullptr);
    ~MainWindow() override;

    // Loads a DICOM folder/file/DICOMDIR, .mhd, .nii(.gz) or .inv3 on a worker
    // thread with a cancellable progress dialog; series picks one (id or UID).
    // Errors are shown in a message box. A load still running is cancelled.
    void openPath(const QString& path, const QString& series = {});
    void setVolume(std::shared_ptr<const Volume> volume);
    const std::shared_ptr<const Volume>& volume() const { return volume_; }

    SliceView* view(Orientation orientation) const;
    MprCursor* cursor() const { return cursor_; }

signals:
    // After every load attempt: ok is false on error or cancel.
    void loadFinished(bool ok);

private:
    void openFolderDialog();
    void openFileDialog();
    void showProgress();
    void finishLoad(std::uint64_t id, std::shared_ptr<Volume> volume, const QString& error,
                    bool cancelled);

    MprCursor* cursor_;
    std::array<SliceView*, 3> views_{};
    VolumeView* volumeView_ = nullptr;
    TransferFunctionEditor* tfEditor_ = nullptr;
    QLabel* info_;
    QPointer<QProgressDialog> progress_;
    std::shared_ptr<const Volume> volume_;
    QString loadingPath_;

    // Written by the worker, read on the GUI thread.
    std::mutex progressMutex_;
    LoadProgress latestProgress_;
    bool progressPosted_ = false;
    std::uint64_t loadId_ = 0;

    // Last, so that it is joined (after a stop request) before anything else goes.
    std::jthread worker_;
};

} // namespace lucent
