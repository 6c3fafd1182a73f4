#include "ui/MainWindow.h"

#include <filesystem>

#include <QApplication>
#include <QDockWidget>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QProgressDialog>
#include <QSplitter>
#include <QStatusBar>
#include <QVBoxLayout>

#include "core/io/Catalog.h"
#include "ui/MprCursor.h"
#include "ui/PacsBrowser.h"
#include "ui/SliceView.h"
#include "ui/TransferFunctionEditor.h"
#include "ui/VolumeView.h"
#include "ui/VolumeViewControls.h"

namespace lucent {

namespace {

QString describe(const Volume& v) {
    const glm::ivec3& d = v.dims();
    const glm::dvec3& s = v.geometry().spacing;
    QStringList parts;
    if (!v.patientName.empty() || !v.patientId.empty()) {
        parts << QString::fromStdString(v.patientName +
                                        (v.patientId.empty() ? "" : " (" + v.patientId + ")"))
                     .trimmed();
    }
    const QString series = QStringLiteral("%1 %2").arg(QString::fromStdString(v.modality),
                                                       QString::fromStdString(v.description));
    if (!series.trimmed().isEmpty()) {
        parts << series.trimmed();
    }
    if (!v.studyDate.empty()) {
        parts << QString::fromStdString(v.studyDate);
    }
    parts << QStringLiteral("%1 x %2 x %3").arg(d.x).arg(d.y).arg(d.z);
    parts << QStringLiteral("%1 x %2 x %3 mm")
                 .arg(s.x, 0, 'g', 4)
                 .arg(s.y, 0, 'g', 4)
                 .arg(s.z, 0, 'g', 4);
    if (!v.warnings.empty()) {
        parts << QCoreApplication::translate("lucent::MainWindow", "%n warning(s)", nullptr,
                                             static_cast<int>(v.warnings.size()));
    }
    return parts.join(QStringLiteral("   |   "));
}

} // namespace

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent), cursor_(new MprCursor(this)), info_(new QLabel(this)) {
    setWindowTitle(QStringLiteral("Lucent"));
    // 2x2: axial and coronal above, sagittal and the 3D view below.
    auto* rows = new QSplitter(Qt::Vertical, this);
    auto* top = new QSplitter(Qt::Horizontal, rows);
    auto* bottom = new QSplitter(Qt::Horizontal, rows);
    for (QSplitter* s : {rows, top, bottom}) {
        s->setHandleWidth(2);
    }
    const std::array<Orientation, 3> orientations{Orientation::Axial, Orientation::Coronal,
                                                  Orientation::Sagittal};
    for (std::size_t n = 0; n < views_.size(); ++n) {
        QSplitter* row = n < 2 ? top : bottom;
        views_[n] = new SliceView(orientations[n], cursor_, row);
        row->addWidget(views_[n]);
    }
    volumeView_ = new VolumeView(bottom);
    bottom->addWidget(volumeView_);
    for (QSplitter* s : {rows, top, bottom}) {
        s->setSizes({1000, 1000}); // four views of one size (scaled to fit)
    }
    setCentralWidget(rows);

    // The 3D view's controls and the transfer-function editor in a dock.
    tfEditor_ = new TransferFunctionEditor;
    auto* panel = new QWidget;
    auto* column = new QVBoxLayout(panel);
    column->addWidget(new VolumeViewControls(volumeView_, panel));
    column->addWidget(tfEditor_, 1);
    auto* dock = new QDockWidget(tr("3D / Transfer function"), this);
    dock->setObjectName(QStringLiteral("volumeDock"));
    dock->setWidget(panel);
    addDockWidget(Qt::RightDockWidgetArea, dock);
    connect(tfEditor_, &TransferFunctionEditor::transferFunctionChanged, volumeView_,
            &VolumeView::setTransferFunction);
    connect(volumeView_, &VolumeView::transferFunctionChanged, tfEditor_,
            &TransferFunctionEditor::setTransferFunction);
    statusBar()->addWidget(info_, 1);
    info_->setText(tr("No volume. Open a DICOM folder, a file or an InVesalius project."));
    info_->setTextInteractionFlags(Qt::TextSelectableByMouse);

    QMenu* file = menuBar()->addMenu(tr("&File"));
    file->addAction(tr("Open &Folder..."), QKeySequence(tr("Ctrl+Shift+O")), this,
                    &MainWindow::openFolderDialog);
    file->addAction(tr("&Open File..."), QKeySequence::Open, this, &MainWindow::openFileDialog);
    file->addSeparator();
    file->addAction(tr("&Quit"), QKeySequence::Quit, qApp, &QApplication::closeAllWindows);
    // PACS query/retrieve and the local store in a dock; arrived series open here.
    PacsBrowser* pacs = PacsBrowser::addDock(this, menuBar()->addMenu(tr("&PACS")));
    connect(pacs, &PacsBrowser::openSeries, this,
            [this](const QString& folder, const QString& series) { openPath(folder, series); });
    resize(1500, 1000);
}

MainWindow::~MainWindow() {
    if (worker_.joinable()) {
        worker_.request_stop();
        worker_.join();
    }
}

SliceView* MainWindow::view(Orientation orientation) const {
    return views_[static_cast<std::size_t>(orientation)];
}

void MainWindow::openFolderDialog() {
    const QString dir = QFileDialog::getExistingDirectory(this, tr("Open DICOM folder"));
    if (!dir.isEmpty()) {
        openPath(dir);
    }
}

void MainWindow::openFileDialog() {
    const QString file = QFileDialog::getOpenFileName(
        this, tr("Open volume"), {},
        tr("Volumes (*.dcm *.DCM *.mhd *.nii *.nii.gz *.inv3 DICOMDIR);;All files (*)"));
    if (!file.isEmpty()) {
        openPath(file);
    }
}

void MainWindow::openPath(const QString& path, const QString& series) {
    // A new jthread replaces the old one only after stopping and joining it.
    worker_ = std::jthread();
    const std::uint64_t id = ++loadId_;
    loadingPath_ = path;
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
                                    0, 0, this);
    progress_->setWindowTitle(tr("Opening"));
    progress_->setWindowModality(Qt::WindowModal);
    progress_->setAutoReset(false);
    progress_->setAutoClose(false);
    progress_->setMinimumDuration(300);
    progress_->setValue(0);
    statusBar()->showMessage(tr("Opening %1 ...").arg(path));

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
                QMetaObject::invokeMethod(this, &MainWindow::showProgress, Qt::QueuedConnection);
            }
        };
        std::shared_ptr<Volume> volume;
        QString error;
        bool cancelled = false;
        try {
            volume = std::make_shared<Volume>(loadPath(file, wanted, control));
        } catch (const LoadCancelled&) {
            cancelled = true;
        } catch (const std::exception& e) {
            error = QString::fromStdString(e.what());
        }
        QMetaObject::invokeMethod(
            this,
            [this, id, volume, error, cancelled] { finishLoad(id, volume, error, cancelled); },
            Qt::QueuedConnection);
    });
    // The dialog's cancel asks the worker's stop_source to stop.
    connect(progress_, &QProgressDialog::canceled, this, [this, id] {
        if (id == loadId_) {
            worker_.request_stop();
            statusBar()->showMessage(tr("Cancelling ..."));
        }
    });
}

void MainWindow::showProgress() {
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
    progress_->setLabelText(tr("Opening %1\n%2").arg(QFileInfo(loadingPath_).fileName(), stage));
    // QProgressDialog counts in int; scale large totals down.
    const std::size_t scale = p.total > 1'000'000 ? p.total / 1'000'000 : 1;
    progress_->setMaximum(static_cast<int>(p.total / scale));
    progress_->setValue(static_cast<int>(std::min(p.done, p.total) / scale));
}

void MainWindow::finishLoad(std::uint64_t id, std::shared_ptr<Volume> volume, const QString& error,
                            bool cancelled) {
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
        statusBar()->clearMessage();
        setVolume(std::move(volume));
        emit loadFinished(true);
        return;
    }
    if (cancelled) {
        statusBar()->showMessage(tr("Opening %1 was cancelled").arg(loadingPath_), 5000);
    } else {
        statusBar()->clearMessage();
        QMessageBox::critical(this, tr("Cannot open"),
                              tr("Could not open %1:\n\n%2").arg(loadingPath_, error));
    }
    emit loadFinished(false);
}

void MainWindow::setVolume(std::shared_ptr<const Volume> volume) {
    volume_ = std::move(volume);
    if (volume_ && !volume_->empty()) {
        // Start at the middle voxel, so that thin slices fall on voxel centres.
        cursor_->setPoint(volume_->geometry().toPatient(glm::dvec3(volume_->dims() / 2)));
        const WindowLevel window = defaultWindow(*volume_);
        cursor_->setWindowStep(window.step);
        cursor_->setWindow(window.center, window.width);
        info_->setText(describe(*volume_));
        info_->setToolTip(QString::fromStdString([&] {
            std::string all;
            for (const std::string& w : volume_->warnings) {
                all += (all.empty() ? "" : "\n") + w;
            }
            return all;
        }()));
        const QString title = QString::fromStdString(volume_->description);
        setWindowTitle(title.isEmpty() ? QStringLiteral("Lucent")
                                       : QStringLiteral("%1 - Lucent").arg(title));
    } else {
        info_->setText(tr("No volume."));
        info_->setToolTip({});
        setWindowTitle(QStringLiteral("Lucent"));
    }
    for (SliceView* view : views_) {
        view->setVolume(volume_);
    }
    volumeView_->setVolume(volume_); // picks ct-bone or mr-default and tells the editor
    tfEditor_->setVolume(volume_);   // the histogram
}

} // namespace lucent
