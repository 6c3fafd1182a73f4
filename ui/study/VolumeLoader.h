#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>

#include <QObject>
#include <QPointer>
#include <QString>

#include "core/io/LoadControl.h"
#include "core/volume/Volume.h"

class QMessageBox;
class QProgressDialog;
class QWidget;

namespace lucent {

// Opens a DICOM folder/file/DICOMDIR, .mhd, .nii(.gz) or .inv3 on a worker thread,
// with a window-modal progress dialog whose Cancel stops the work. A failure is
// shown in a window-modal message box over `window` (objectName "loadErrorDialog")
// with the error and, as details, the path and every file the scan did not use;
// it does not block, so the window stays usable.
class VolumeLoader : public QObject {
    Q_OBJECT

public:
    explicit VolumeLoader(QWidget* window);
    ~VolumeLoader() override;

    // series picks one (id or UID; empty: the largest volume). A load still
    // running is cancelled and its result dropped.
    void load(const QString& path, const QString& series = {});
    const QString& path() const { return path_; }

signals:
    void loaded(std::shared_ptr<lucent::Volume> volume);
    // After every load attempt: ok is false on error or cancel.
    void finished(bool ok);
    // A line for the status bar (timeoutMs 0: until the next one).
    void status(const QString& message, int timeoutMs);

private:
    void showProgress();
    void finish(std::uint64_t id, std::shared_ptr<Volume> volume, const QString& error,
                const QString& details, bool cancelled);
    void showError(const QString& error, const QString& details);

    QWidget* window_;
    QPointer<QProgressDialog> progress_;
    QPointer<QMessageBox> error_;
    QString path_;

    // Written by the worker, read on the GUI thread.
    std::mutex progressMutex_;
    LoadProgress latestProgress_;
    bool progressPosted_ = false;
    std::uint64_t loadId_ = 0;

    // Last, so that it is joined (after a stop request) before anything else goes.
    std::jthread worker_;
};

} // namespace lucent
