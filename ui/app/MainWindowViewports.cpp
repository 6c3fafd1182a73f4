// MainWindow: what the viewport grid's viewports share with the MPR layout (the series'
// measurements, curved MPR, the measurement list following the active viewport) and the
// RECIST follow-up dock, whose lesions open in the grid, the priors timeline, the Fusion
// dock and the Segments dock.
#include "ui/app/MainWindow.h"

#include <QDockWidget>
#include <QStatusBar>

#include <QFileInfo>
#include <QInputDialog>
#include <QMenu>
#include <QScrollArea>
#include <QStandardPaths>

#include "core/hanging/HangingProtocolJson.h"
#include "core/store/StudyStore.h"
#include "ui/app/MeasurementControls.h"
#include "ui/followup/FollowUpPanel.h"
#include "ui/fusion/FusionPanel.h"
#include "ui/fusion/ViewportFusion.h"
#include "ui/mpr/MeasurementAutosave.h"
#include "ui/mpr/MeasurementList.h"
#include "ui/mpr/SeriesMeasurements.h"
#include "ui/mpr/SliceView.h"
#include "ui/priors/PriorTimeline.h"
#include "ui/segmentation/SegmentEditor.h"
#include "ui/segmentation/SegmentTools3d.h"
#include "ui/segmentation/SegmentationAutosave.h"
#include "ui/segmentation/SegmentationStoreSync.h"
#include "ui/segmentation/SegmentsPanel.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/StudyHanging.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportWorkspace.h"

namespace lucent {

SeriesMeasurements* MainWindow::measurementsFor(const std::shared_ptr<const Volume>& volume) {
    if (!volume || volume->empty()) {
        return nullptr;
    }
    // A series without a UID gets measurements of its own each time it is opened.
    const auto known = volume->seriesUid.empty() ? seriesMeasurements_.end()
                                                 : seriesMeasurements_.find(volume->seriesUid);
    if (known != seriesMeasurements_.end()) {
        return known->second;
    }
    auto* made = new SeriesMeasurements(volume, this);
    if (!volume->seriesUid.empty()) {
        seriesMeasurements_[volume->seriesUid] = made;
    }
    emit measurementsOpened(made);
    return made;
}

void MainWindow::showMeasurementsOf(const std::shared_ptr<const Volume>& volume) {
    SeriesMeasurements* shown = measurementsFor(volume);
    if (shown != nullptr) {
        shown->setVolume(volume);
    }
    SeriesMeasurements* before = measurements_;
    measurements_ = shown;
    measurementControls_->setMeasurements(shown);
    if (before != nullptr && before != shown && before->seriesUid().empty()) {
        before->deleteLater(); // nothing can open it again
    }
    if (followUp_ != nullptr && volume) {
        followUp_->showPatient(QString::fromStdString(volume->patientId));
    }
}

void MainWindow::addFollowUpDock(const QString& storeFolder) {
    storeFolder_ = storeFolder;
    followUp_ = new FollowUpPanel;
    followUp_->setStoreFolder(storeFolder);
    auto* dock = new QDockWidget(tr("Follow-up"), this); // the RECIST 1.1 table
    dock->setObjectName(QStringLiteral("followUpDock"));
    dock->setWidget(followUp_);
    // A tab beside the measurement list: the reading area keeps its size.
    addDockWidget(Qt::RightDockWidgetArea, dock);
    if (auto* list = findChild<QDockWidget*>(QStringLiteral("measurementDock"))) {
        tabifyDockWidget(list, dock);
    }
    if (auto* volumeDock = findChild<QDockWidget*>(QStringLiteral("volumeDock"))) {
        volumeDock->raise();
    }
    connect(autosave_, &MeasurementAutosave::saved, followUp_, &FollowUpPanel::refresh);
    measurementControls_->list()->setLesionChoices(
        [panel = followUp_](const std::string& seriesUid) {
            return panel->earlierLesions(seriesUid);
        });
    connect(
        followUp_, &FollowUpPanel::lesionActivated, this,
        [this](const QString&, const std::vector<LesionLocation>& where) { goToLesion(where); });
}

void MainWindow::addPriorsDock(PriorsForStudy& priors) {
    priorTimeline_ = new PriorTimeline(priors);
    auto* dock = new QDockWidget(tr("Priors"), this);
    dock->setObjectName(QStringLiteral("priorsDock"));
    dock->setWidget(priorTimeline_);
    addDockWidget(Qt::RightDockWidgetArea, dock);
    if (auto* followUp = findChild<QDockWidget*>(QStringLiteral("followUpDock"))) {
        tabifyDockWidget(followUp, dock);
    }
    if (auto* volumeDock = findChild<QDockWidget*>(QStringLiteral("volumeDock"))) {
        volumeDock->raise();
    }
    // A study picked on the timeline goes into the active viewport, beside what is there.
    connect(priorTimeline_, &PriorTimeline::openStudy, this,
            [this](const QString& folder, const QString& series) {
                showWorkspace(true);
                workspace_->showInActive(folder, series);
            });
}

void MainWindow::addFusionDock() {
    fusion_ = new ViewportFusion(workspace_, this);
    fusionPanel_ = new FusionPanel(workspace_, fusion_);
    auto* dock = new QDockWidget(tr("Fusion"), this);
    dock->setObjectName(QStringLiteral("fusionDock"));
    dock->setWidget(fusionPanel_);
    addDockWidget(Qt::RightDockWidgetArea, dock);
    if (auto* followUp = findChild<QDockWidget*>(QStringLiteral("followUpDock"))) {
        tabifyDockWidget(followUp, dock);
    }
    if (auto* volumeDock = findChild<QDockWidget*>(QStringLiteral("volumeDock"))) {
        volumeDock->raise();
    }
    connect(fusionPanel_, &FusionPanel::message, this,
            [this](const QString& text, int ms) { statusBar()->showMessage(text, ms); });
}

void MainWindow::addSegmentsDock() {
    // Segments of stored series are kept there as DICOM SEG as the reader works. Made before
    // the editor: children go in the order they came, so its last save finds the sessions.
    segmentAutosave_ = new SegmentationAutosave(storeFolder_, this);
    segmentEditor_ = new SegmentEditor(workspace_, this);
    segmentsPanel_ = new SegmentsPanel(segmentEditor_);
    auto* storeSync = new SegmentationStoreSync(segmentEditor_->sessions(), segmentAutosave_, this);
    connect(storeSync, &SegmentationStoreSync::message, this,
            [this](const QString& text, int ms) { statusBar()->showMessage(text, ms); });
    segmentTools3d_ = new SegmentTools3d(
        segmentsPanel_, [this](const Volume& series) { return volumeViewOf(series); });
    segmentsPanel_->addEffectWidget(segmentTools3d_);
    connect(segmentTools3d_, &SegmentTools3d::message, this,
            [this](const QString& text, int ms) { statusBar()->showMessage(text, ms); });
    auto* dock = new QDockWidget(tr("Segments"), this);
    dock->setObjectName(QStringLiteral("segmentsDock"));
    // Scrolled: its list, effects and statistics would otherwise set the window's minimum.
    auto* scroll = new QScrollArea;
    scroll->setWidget(segmentsPanel_);
    scroll->setWidgetResizable(true);
    scroll->setFrameShape(QFrame::NoFrame);
    dock->setWidget(scroll);
    addDockWidget(Qt::RightDockWidgetArea, dock);
    if (auto* fusionDock = findChild<QDockWidget*>(QStringLiteral("fusionDock"))) {
        tabifyDockWidget(fusionDock, dock);
    }
    // Closed until View > Segments opens it: a sixth tab would widen the dock area.
    dock->hide();
    if (auto* volumeDock = findChild<QDockWidget*>(QStringLiteral("volumeDock"))) {
        volumeDock->raise();
    }
    // A closed dock leaves the views' left button to them again.
    connect(dock, &QDockWidget::visibilityChanged, segmentEditor_, [this](bool visible) {
        if (!visible) {
            segmentEditor_->setTool(SegmentTool::None);
        }
    });
    connect(segmentsPanel_, &SegmentsPanel::message, this,
            [this](const QString& text, int ms) { statusBar()->showMessage(text, ms); });
}

VolumeView* MainWindow::volumeViewOf(const Volume& series) const {
    for (Viewport* viewport : workspace_->grid()->viewports()) {
        if (viewport->volumeView() != nullptr && viewport->session() != nullptr &&
            viewport->session()->volume() &&
            viewport->session()->volume()->seriesUid == series.seriesUid) {
            return viewport->volumeView();
        }
    }
    const bool mainPage = volume_ && volume_->seriesUid == series.seriesUid;
    return mainPage ? volumeView_ : nullptr;
}

void MainWindow::goToLesion(const std::vector<LesionLocation>& where) {
    std::vector<ViewportWorkspace::SeriesPoint> points;
    try {
        const StudyStore store(storeFolder_.toStdString());
        for (const LesionLocation& at : where) {
            points.push_back(
                {QString::fromStdString(store.seriesFolder(at.studyUid, at.seriesUid).string()),
                 QString::fromStdString(at.seriesUid), at.centre});
        }
    } catch (const StoreError& e) {
        statusBar()->showMessage(QString::fromUtf8(e.what()), 8000);
        return;
    }
    showWorkspace(true);
    workspace_->goTo(points);
}

void MainWindow::viewportContentChanged(Viewport* viewport) {
    SliceView* view = viewport->sliceView();
    if (view == nullptr || viewport->session() == nullptr) {
        return;
    }
    const std::shared_ptr<const Volume> volume = viewport->session()->volume();
    view->setMeasurements(measurementsFor(volume));
    connect(view, &SliceView::curvedPathDrawn, this,
            [this, volume](const std::vector<glm::dvec3>& points, const glm::dvec3& up) {
                openCurvedMpr(volume, points, up);
            });
}

void MainWindow::openStudy(const QString& path) {
    lastFolder_ = QFileInfo(path).isDir() ? QFileInfo(path).absoluteFilePath()
                                          : QFileInfo(path).absolutePath();
    showWorkspace(true);
    workspace_->setCaption(tr("Opening %1...").arg(path));
    hanging_->open(path);
}

void MainWindow::addHangingMenu(QMenu* menu) {
    menu->addAction(tr("&Next Protocol"), QKeySequence(tr("Alt+Down")), this,
                    [this] { hanging_->stepProtocol(1); });
    menu->addAction(tr("&Previous Protocol"), QKeySequence(tr("Alt+Up")), this,
                    [this] { hanging_->stepProtocol(-1); });
    menu->addAction(tr("Next &Viewport Set"), QKeySequence(tr("Alt+Right")), this,
                    [this] { hanging_->stepViewportSet(1); });
    menu->addAction(tr("Previous Viewport &Set"), QKeySequence(tr("Alt+Left")), this,
                    [this] { hanging_->stepViewportSet(-1); });
    menu->addSeparator();
    menu->addAction(tr("Save &Layout as Protocol..."), this, [this] {
        const QString name =
            QInputDialog::getText(this, tr("Save layout as protocol"), tr("Protocol name:"));
        if (name.trimmed().isEmpty()) {
            return;
        }
        QString error;
        const QString file = hanging_->saveLayout(name.trimmed(), &error);
        statusBar()->showMessage(file.isEmpty() ? tr("Not saved: %1").arg(error)
                                                : tr("Saved protocol %1").arg(file),
                                 8000);
    });
}

void MainWindow::wireViewports(PacsService* service) {
    hanging_ = new StudyHanging(
        workspace_, service,
        QString::fromStdString(
            userHangingFolder(
                QStandardPaths::writableLocation(QStandardPaths::GenericDataLocation).toStdString())
                .string()),
        this);
    connect(hanging_, &StudyHanging::message, this,
            [this](const QString& text, int ms) { statusBar()->showMessage(text, ms); });
    connect(hanging_, &StudyHanging::hung, this, [this](const QString& protocol, qint64 ms) {
        statusBar()->showMessage(tr("%1: hung in %2 ms").arg(protocol).arg(ms), 8000);
    });
    // The MPR layout of one series is the main window's own page.
    connect(hanging_, &StudyHanging::mprRequested, this,
            [this](const QString& path, const QString& series) {
                showWorkspace(false);
                if (!volume_ || QString::fromStdString(volume_->seriesUid) != series) {
                    openPath(path, series);
                }
            });
    if (hanging_->priors() != nullptr) {
        addPriorsDock(*hanging_->priors());
    }
    addFusionDock();
    addSegmentsDock();
    ViewportGrid* grid = workspace_->grid();
    connect(grid, &ViewportGrid::viewportContentChanged, this, &MainWindow::viewportContentChanged);
    // The measurement list, its tools and the follow-up show the active viewport's series.
    connect(grid, &ViewportGrid::activeViewportChanged, this, [this](Viewport* active) {
        if (active != nullptr && active->session() != nullptr && active->session()->volume() &&
            workspaceShown()) {
            SeriesMeasurements* shown = measurementsFor(active->session()->volume());
            measurements_ = shown;
            measurementControls_->setMeasurements(shown);
            followUp_->showPatient(QString::fromStdString(active->session()->volume()->patientId));
        }
    });
}

} // namespace lucent
