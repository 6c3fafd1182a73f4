#include "ui/app/MainWindow.h"

#include <QActionGroup>
#include <QApplication>
#include <QCloseEvent>
#include <QDir>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QMenuBar>
#include <QMessageBox>
#include <QSettings>
#include <QStackedWidget>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTabWidget>
#include <QVBoxLayout>

#include "core/pacs/PacsService.h"
#include "core/pet/PetDisplay.h"
#include "ui/app/MeasurementControls.h"
#include "ui/app/MovieExportDialog.h"
#include "ui/app/ScreenshotExport.h"
#include "ui/app/ShortcutsDialog.h"
#include "ui/app/ViewLayout.h"
#include "ui/mpr/CurvedMprView.h"
#include "ui/mpr/MeasurementAutosave.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SeriesMeasurements.h"
#include "ui/mpr/SliceView.h"
#include "ui/pacs/PacsBrowser.h"
#include "ui/study/StudyBrowser.h"
#include "ui/study/VolumeLoader.h"
#include "ui/theme/Theme.h"
#include "ui/theme/ThemeMenu.h"
#include "ui/transfer/TransferFunctionEditor.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportLinks.h"
#include "ui/viewports/ViewportWorkspace.h"
#include "ui/volume/RenderServerSettings.h"
#include "ui/volume/RotatingMip.h"
#include "ui/volume/SurfacePanel.h"
#include "ui/volume/VolumeView.h"
#include "ui/volume/VolumeViewControls.h"

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
    if (v.pet) {
        parts << QString::fromStdString(v.pet->unit());
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

QString folderOf(const QString& path) {
    const QFileInfo info(path);
    return info.isDir() ? info.absoluteFilePath() : info.absolutePath();
}

} // namespace

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent), cursor_(new MprCursor(this)), info_(new QLabel(this)) {
    setWindowTitle(QStringLiteral("Lucent"));
    // The saved look (dark unless the user chose light) before any widget is polished.
    applyTheme(*qApp, savedTheme());
    const std::array<Orientation, 3> orientations{Orientation::Axial, Orientation::Coronal,
                                                  Orientation::Sagittal};
    for (std::size_t n = 0; n < views_.size(); ++n) {
        views_[n] = new SliceView(orientations[n], cursor_, this);
        connect(views_[n], &SliceView::curvedPathDrawn, this,
                [this](const std::vector<glm::dvec3>& points, const glm::dvec3& up) {
                    openCurvedMpr(volume_, points, up);
                });
    }
    volumeView_ = new VolumeView(this);
    layout_ = new ViewLayout({views_[0], views_[1], views_[2], volumeView_}, this);
    workspace_ = new ViewportWorkspace(this);
    central_ = new QStackedWidget(this);
    central_->addWidget(layout_);
    central_->addWidget(workspace_);
    setCentralWidget(central_);
    connect(
        workspace_, &ViewportWorkspace::message, this,
        [this](const QString& text, int timeoutMs) { statusBar()->showMessage(text, timeoutMs); });

    // The 3D view's controls and the transfer-function editor in a dock.
    tfEditor_ = new TransferFunctionEditor;
    auto* panel = new QWidget;
    auto* column = new QVBoxLayout(panel);
    // The view's controls and the Surface panel share the top of the dock.
    auto* tabs = new QTabWidget(panel);
    tabs->addTab(new VolumeViewControls(volumeView_, tabs), tr("View"));
    tabs->addTab(new SurfacePanel(volumeView_, tabs), tr("Surface"));
    column->addWidget(tabs);
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
    loader_ = new VolumeLoader(this);
    // Patients, studies and series of the local store and of the folders opened,
    // with thumbnails; a click opens one.
    auto* studyDock = new QDockWidget(tr("Studies"), this);
    auto* studies = new StudyBrowser(studyDock);
    studyDock->setObjectName(QStringLiteral("studyDock"));
    studyDock->setWidget(studies);
    addDockWidget(Qt::LeftDockWidgetArea, studyDock);
    connect(studies, &StudyBrowser::openRequested, this,
            [this, studies](const QString& path, const QString& series) {
                if (workspaceShown() || studies->opensAsStack(path, series)) {
                    // The grid's active viewport (2D images open only there).
                    showWorkspace(true);
                    workspace_->showInActive(path, series);
                } else {
                    openPath(path, series);
                }
            });
    connect(loader_, &VolumeLoader::loaded, this, [this, studies](std::shared_ptr<Volume> volume) {
        studies->addSeries(loader_->path(), *volume);
        setVolume(std::move(volume));
    });
    connect(loader_, &VolumeLoader::finished, this, &MainWindow::loadFinished);
    connect(loader_, &VolumeLoader::status, this, [this](const QString& message, int timeoutMs) {
        statusBar()->showMessage(message, timeoutMs);
    });
    info_->setText(tr("No volume. Open a DICOM folder, a file or an InVesalius project."));
    info_->setTextInteractionFlags(Qt::TextSelectableByMouse);

    QMenu* file = menuBar()->addMenu(tr("&File"));
    file->addAction(tr("Open &Folder..."), QKeySequence(tr("Ctrl+Shift+O")), this,
                    &MainWindow::openFolderDialog);
    file->addAction(tr("&Open File..."), QKeySequence::Open, this, &MainWindow::openFileDialog);
    file->addAction(tr("Open &Study (Hanging Protocol, Priors)..."), QKeySequence(tr("Ctrl+Alt+O")),
                    this, [this] {
                        const QString dir =
                            QFileDialog::getExistingDirectory(this, tr("Open study"), lastFolder_);
                        if (!dir.isEmpty()) {
                            openStudy(dir);
                        }
                    });
    file->addSeparator();
    file->addAction(tr("Save Screenshot of Active &View..."), QKeySequence(tr("Ctrl+Shift+E")),
                    this, [this] { screenshotDialog(ScreenshotScope::ActiveView); });
    file->addAction(tr("Save Screenshot of &Layout..."), QKeySequence(tr("Ctrl+Alt+E")), this,
                    [this] { screenshotDialog(ScreenshotScope::Layout); });
    file->addAction(tr("Export &Movie..."), QKeySequence(tr("Ctrl+Shift+M")), this,
                    &MainWindow::openMovieExport);
    file->addSeparator();
    file->addAction(tr("&Quit"), QKeySequence::Quit, qApp, &QApplication::closeAllWindows);
    measurementControls_ =
        new MeasurementControls(this, cursor_, views_, menuBar()->addMenu(tr("&Edit")));
    // PACS query/retrieve and the local store in a dock; arrived series open here.
    PacsBrowser* pacs = PacsBrowser::addDock(this, menuBar()->addMenu(tr("&PACS")));
    studies->setStoreFolder(pacs->config().storeFolder);
    workspace_->links()->setStoreFolder(pacs->config().storeFolder); // "link here" offsets
    // Measurements of stored series are kept there as DICOM SR, as the reader works.
    autosave_ = new MeasurementAutosave(pacs->config().storeFolder, this);
    connect(this, &MainWindow::measurementsOpened, autosave_, &MeasurementAutosave::attach);
    connect(
        autosave_, &MeasurementAutosave::message, this,
        [this](const QString& text, int timeoutMs) { statusBar()->showMessage(text, timeoutMs); });
    connect(pacs->service(), &PacsService::retrievalFinished, studies, &StudyBrowser::refreshStore);
    connect(pacs, &PacsBrowser::openSeries, this,
            [this](const QString& folder, const QString& series) { openPath(folder, series); });
    addFollowUpDock(pacs->config().storeFolder);
    wireViewports(pacs->service());
    addViewMenu();
    QMenu* help = menuBar()->addMenu(tr("&Help"));
    help->addAction(tr("&Keyboard Shortcuts..."), QKeySequence(QKeySequence::HelpContents), this,
                    &MainWindow::showShortcuts);
    resize(1500, 1000);
    restoreSettings();
}

void MainWindow::addViewMenu() {
    QMenu* menu = menuBar()->addMenu(tr("&View"));
    layoutActions_ = new QActionGroup(this);
    const std::array<std::pair<ViewLayout::Arrangement, QString>, 3> layouts{{
        {ViewLayout::Arrangement::Grid2x2, tr("&2 x 2: Axial, Coronal, Sagittal, 3D")},
        {ViewLayout::Arrangement::Row1x3, tr("1 x &3: Axial, Coronal, Sagittal")},
        {ViewLayout::Arrangement::Single, tr("1 x &1: Active View")},
    }};
    int key = Qt::Key_1;
    for (const auto& [arrangement, text] : layouts) {
        QAction* action = menu->addAction(text);
        action->setShortcut(QKeySequence(Qt::CTRL | static_cast<Qt::Key>(key++)));
        action->setCheckable(true);
        action->setChecked(arrangement == layout_->arrangement());
        action->setData(ViewLayout::name(arrangement));
        layoutActions_->addAction(action);
        connect(action, &QAction::triggered, layout_,
                [this, arrangement] { layout_->setArrangement(arrangement); });
    }
    for (QAction* action : layoutActions_->actions()) {
        connect(action, &QAction::triggered, this, [this] { showWorkspace(false); });
    }
    QMenu* grid = menu->addMenu(tr("Viewport &Grid"));
    workspace_->fillMenu(grid);
    addHangingMenu(menu->addMenu(tr("&Hanging Protocols")));
    for (QAction* action : grid->actions()) {
        if (action->objectName().startsWith(QStringLiteral("grid-"))) {
            connect(action, &QAction::triggered, this, [this] { showWorkspace(true); });
        }
    }
    connect(layout_, &ViewLayout::arrangementChanged, this,
            [this](ViewLayout::Arrangement arrangement) {
                for (QAction* action : layoutActions_->actions()) {
                    action->setChecked(action->data().toString() == ViewLayout::name(arrangement));
                }
            });
    menu->addAction(tr("&Maximize or Restore Active View"), QKeySequence(tr("Ctrl+0")), layout_,
                    [this] {
                        if (layout_->maximized()) {
                            layout_->restore();
                        } else {
                            layout_->maximize(layout_->activeView());
                        }
                    });
    menu->addAction(volumeView_->rotatingMip()->action()); // the PET cine in the 3D view
    addRenderBackendMenu(menu, volumeView_);               // this computer or a render server
    addThemeMenu(menu);                                    // dark or light, saved at once
    menu->addSeparator();
    for (QDockWidget* dock : findChildren<QDockWidget*>()) {
        menu->addAction(dock->toggleViewAction());
    }
}

void MainWindow::saveSettings() const {
    QSettings settings;
    settings.setValue(QStringLiteral("window/geometry"), saveGeometry());
    settings.setValue(QStringLiteral("window/state"), saveState());
    // A maximized view is saved as 1x1 of that view.
    settings.setValue(QStringLiteral("view/layout"), ViewLayout::name(layout_->arrangement()));
    settings.setValue(QStringLiteral("view/active"), layout_->activeIndex());
    settings.setValue(QStringLiteral("files/lastFolder"), lastFolder_);
    saveTheme(currentTheme());
}

void MainWindow::restoreSettings() {
    const QSettings settings;
    restoreGeometry(settings.value(QStringLiteral("window/geometry")).toByteArray());
    restoreState(settings.value(QStringLiteral("window/state")).toByteArray());
    const int active = settings.value(QStringLiteral("view/active"), 0).toInt();
    if (active >= 0 && active < ViewLayout::kViewCount) {
        layout_->setActiveView(layout_->views()[static_cast<std::size_t>(active)]);
    }
    const auto arrangement =
        ViewLayout::fromName(settings.value(QStringLiteral("view/layout")).toString());
    layout_->setArrangement(arrangement.value_or(ViewLayout::Arrangement::Grid2x2));
    lastFolder_ = settings.value(QStringLiteral("files/lastFolder")).toString();
}

void MainWindow::closeEvent(QCloseEvent* event) {
    saveSettings();
    QMainWindow::closeEvent(event);
}

bool MainWindow::saveScreenshot(const QString& file, ScreenshotScope scope, QString* error) {
    const QImage image =
        scope == ScreenshotScope::ActiveView ? grabView(layout_->activeView()) : grabArea(layout_);
    return writePng(image, file, error);
}

void MainWindow::screenshotDialog(ScreenshotScope scope) {
    const QString folder =
        QStandardPaths::writableLocation(QStandardPaths::PicturesLocation).isEmpty()
            ? lastFolder_
            : QStandardPaths::writableLocation(QStandardPaths::PicturesLocation);
    const QString name = scope == ScreenshotScope::ActiveView ? QStringLiteral("lucent-view.png")
                                                              : QStringLiteral("lucent-layout.png");
    QString file = QFileDialog::getSaveFileName(this, tr("Save screenshot"),
                                                QDir(folder).filePath(name), tr("PNG (*.png)"));
    if (file.isEmpty()) {
        return;
    }
    if (!file.endsWith(QStringLiteral(".png"), Qt::CaseInsensitive)) {
        file += QStringLiteral(".png");
    }
    QString error;
    if (saveScreenshot(file, scope, &error)) {
        statusBar()->showMessage(tr("Saved %1").arg(file), 5000);
    } else {
        QMessageBox::warning(this, tr("Screenshot"), tr("Could not save %1: %2").arg(file, error));
    }
}

MovieExportDialog* MainWindow::openMovieExport() {
    if (!volume_ || volume_->empty()) {
        statusBar()->showMessage(tr("Open a volume to export a movie of it."), 5000);
        return nullptr;
    }
    auto* dialog = new MovieExportDialog(
        volume_, volumeView_->description(),
        WindowLevel{cursor_->windowCenter(), cursor_->windowWidth(), cursor_->windowStep()}, this);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    connect(dialog, &MovieExportDialog::exportFinished, this,
            [this](bool ok, const QString& message) {
                if (ok) {
                    statusBar()->showMessage(message, 8000);
                }
            });
    dialog->show();
    return dialog;
}

MainWindow::~MainWindow() = default;

void MainWindow::openCurvedMpr(const std::shared_ptr<const Volume>& volume,
                               const std::vector<glm::dvec3>& points, const glm::dvec3& up) {
    if (curvedMpr_ == nullptr) {
        curvedMpr_ = new CurvedMprView(cursor_, this);
        curvedMpr_->setWindowFlag(Qt::Window);
        curvedMpr_->resize(900, 640);
    }
    try {
        curvedMpr_->setPath(volume, points, up);
    } catch (const std::invalid_argument& e) {
        statusBar()->showMessage(QString::fromStdString(e.what()), 8000);
        return;
    }
    curvedMpr_->show();
    curvedMpr_->raise();
}

bool MainWindow::workspaceShown() const {
    return central_->currentWidget() == workspace_;
}

void MainWindow::showWorkspace(bool shown) {
    central_->setCurrentWidget(shown ? static_cast<QWidget*>(workspace_) : layout_);
    Viewport* first = workspace_->grid()->viewport(0);
    if (shown && volume_ && !volume_->empty() && first != nullptr && first->session() == nullptr) {
        workspace_->grid()->setActiveViewport(first);
        workspace_->showVolume(volume_, loader_->path(),
                               QString::fromStdString(volume_->seriesUid));
    }
}

SliceView* MainWindow::view(Orientation orientation) const {
    return views_[static_cast<std::size_t>(orientation)];
}

void MainWindow::openFolderDialog() {
    const QString dir =
        QFileDialog::getExistingDirectory(this, tr("Open DICOM folder"), lastFolder_);
    if (!dir.isEmpty()) {
        openPath(dir);
    }
}

void MainWindow::openFileDialog() {
    const QString file = QFileDialog::getOpenFileName(
        this, tr("Open volume"), lastFolder_,
        tr("Volumes (*.dcm *.DCM *.mhd *.nii *.nii.gz *.inv3 DICOMDIR);;All files (*)"));
    if (!file.isEmpty()) {
        openPath(file);
    }
}

void MainWindow::openPath(const QString& path, const QString& series) {
    if (QFileInfo::exists(path)) {
        lastFolder_ = folderOf(path);
        QSettings().setValue(QStringLiteral("files/lastFolder"), lastFolder_);
    }
    loader_->load(path, series);
}

void MainWindow::setVolume(std::shared_ptr<const Volume> volume) {
    volume_ = std::move(volume);
    if (volume_ && !volume_->empty()) {
        centreOn(*cursor_, *volume_);
        info_->setText(describe(*volume_));
        info_->setToolTip(QString::fromStdString([&] {
            std::string all = volume_->pet ? petDisplayNotice(*volume_->pet) : std::string();
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
    showMeasurementsOf(volume_);
    volumeView_->setVolume(volume_); // picks ct-bone or mr-default and tells the editor
    tfEditor_->setVolume(volume_);   // the histogram
    if (volume_ && volume_->pet && !volume_->pet->inSuv()) {
        // Told once, as it opens (after what opening the measurements said); the corner
        // text and the status line's tooltip keep it.
        statusBar()->showMessage(QString::fromStdString(petDisplayNotice(*volume_->pet)), 15000);
    }
}

} // namespace lucent

namespace lucent {

ShortcutsDialog* MainWindow::showShortcuts() {
    if (shortcuts_ == nullptr) {
        shortcuts_ = new ShortcutsDialog(*menuBar(), this);
    }
    shortcuts_->show();
    shortcuts_->raise();
    return shortcuts_;
}

} // namespace lucent
