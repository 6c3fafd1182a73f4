#include "ui/study/VolumeLoader.h"

#include <algorithm>
#include <filesystem>
#include <string>

#include <QFile>
#include <QFileInfo>
#include <QMessageBox>
#include <QProgressDialog>
#include <QWidget>

#include "core/io/Catalog.h"
#include "core/io/DisplayedSeries.h"

namespace lucent {

namespace {

// The files a scan looked at and did not use, for an error's details.
std::string skippedList(const Catalog& catalog) {
    constexpr std::size_t kMostListed = 200;
    if (catalog.skipped.empty()) {
        return {};
    }
    std::string list = "Files not used (" + std::to_string(catalog.skipped.size()) + "):";
    for (std::size_t n = 0; n < std::min(catalog.skipped.size(), kMostListed); ++n) {
        list += "\n" + catalog.skipped[n].file + ": " + catalog.skipped[n].reason;
    }
    if (catalog.skipped.size() > kMostListed) {
        list += "\n...";
    }
    return list;
}

} // namespace

VolumeLoader::VolumeLoader(QWidget* window) : QObject(window), window_(window) {}

VolumeLoader::~VolumeLoader() {
    if (worker_.joinable()) {
        worker_.request_stop();
        worker_.join();
    }
}

void VolumeLoader::load(const QString& path, const QString& series) {
    // A new jthread replaces the old one only after stopping and joining it.
    worker_ = std::jthread();
    const std::uint64_t id = ++loadId_;
    path_ = path;
    {
        const std::lock_guard lock(progressMutex_);
        latestProgress_ = {};
        progressPosted_ = false;
    }
    if (progress_) {
        progress_->disconnect(this);
        progress_->reset();
        progress_->hide();
        progress_->deleteLater();
    }
    progress_ = new QProgressDialog(tr("Opening %1").arg(QFileInfo(path).fileName()), tr("Cancel"),
                                    0, 0, window_);
    progress_->setWindowTitle(tr("Opening"));
    progress_->setWindowModality(Qt::WindowModal);
    progress_->setAutoReset(false);
    progress_->setAutoClose(false);
    progress_->setMinimumDuration(300);
    progress_->setValue(0);
    emit status(tr("Opening %1 ...").arg(path), 0);

    const std::filesystem::path file(QFile::encodeName(path).toStdString());
    const std::string wanted = series.toStdString();
    worker_ = std::jthread([this, id, file, wanted](std::stop_token stop) {
        LoadControl control;
        control.stop = stop;
        control.onProgress = [this](const LoadProgress& p) {
            const std::lock_guard lock(progressMutex_);
            latestProgress_ = p;
            if (!progressPosted_) {
                progressPosted_ = true;
                QMetaObject::invokeMethod(this, &VolumeLoader::showProgress, Qt::QueuedConnection);
            }
        };
        std::shared_ptr<Volume> volume;
        std::string error;
        std::string details; // the files the scan did not use
        bool cancelled = false;
        try {
            const Catalog catalog = scanPath(file, control);
            details = skippedList(catalog);
            const SeriesEntry* entry =
                wanted.empty() ? catalog.defaultEntry() : catalog.find(wanted);
            if (entry == nullptr) {
                throw LoadError(file.string() + (wanted.empty()
                                                     ? ": nothing loadable"
                                                     : ": no series with id or UID " + wanted));
            }
            volume = std::make_shared<Volume>(loadDisplayedSeries(*entry, control));
        } catch (const LoadCancelled&) {
            cancelled = true;
        } catch (const std::exception& e) {
            error = e.what();
        }
        QMetaObject::invokeMethod(
            this,
            [this, id, volume, error = QString::fromStdString(error),
             details = QString::fromStdString(details),
             cancelled] { finish(id, volume, error, details, cancelled); },
            Qt::QueuedConnection);
    });
    // The dialog's cancel asks the worker's stop_source to stop.
    connect(progress_, &QProgressDialog::canceled, this, [this, id] {
        if (id == loadId_) {
            worker_.request_stop();
            emit status(tr("Cancelling ..."), 0);
        }
    });
}

void VolumeLoader::showProgress() {
    LoadProgress p;
    {
        const std::lock_guard lock(progressMutex_);
        p = latestProgress_;
        progressPosted_ = false;
    }
    if (!progress_ || progress_->wasCanceled()) {
        return;
    }
    const QString stage = QString::fromStdString(p.stage);
    progress_->setLabelText(tr("Opening %1\n%2").arg(QFileInfo(path_).fileName(), stage));
    // QProgressDialog counts in int; scale large totals down.
    const std::size_t scale = p.total > 1'000'000 ? p.total / 1'000'000 : 1;
    progress_->setMaximum(static_cast<int>(p.total / scale));
    progress_->setValue(static_cast<int>(std::min(p.done, p.total) / scale));
}

void VolumeLoader::finish(std::uint64_t id, std::shared_ptr<Volume> volume, const QString& error,
                          const QString& details, bool cancelled) {
    if (id != loadId_) {
        return; // a load that was replaced by a newer one
    }
    if (progress_) {
        // reset() also stops the timer that would show the dialog after minimumDuration.
        // Deleted later: this may run inside the dialog's own setValue().
        QProgressDialog* dialog = progress_;
        progress_ = nullptr;
        dialog->disconnect(this);
        dialog->reset();
        dialog->hide();
        dialog->deleteLater();
    }
    if (volume) {
        emit status({}, 0);
        emit loaded(std::move(volume));
        emit finished(true);
        return;
    }
    if (cancelled) {
        emit status(tr("Opening %1 was cancelled").arg(path_), 5000);
    } else {
        emit status(tr("Could not open %1").arg(path_), 10000);
        showError(error, details);
    }
    emit finished(false);
}

void VolumeLoader::showError(const QString& error, const QString& details) {
    if (error_) {
        error_->close(); // the newest error replaces an older one
    }
    error_ = new QMessageBox(QMessageBox::Critical, tr("Cannot open"),
                             tr("Could not open %1").arg(path_), QMessageBox::Ok, window_);
    error_->setObjectName(QStringLiteral("loadErrorDialog"));
    error_->setAttribute(Qt::WA_DeleteOnClose);
    error_->setInformativeText(error);
    QString text = tr("Path: %1\n\n%2").arg(QFileInfo(path_).absoluteFilePath(), error);
    if (!details.isEmpty()) {
        text += QStringLiteral("\n\n") + details;
    }
    error_->setDetailedText(text);
    error_->open(); // window-modal, does not block: the window stays usable behind it
}

} // namespace lucent
