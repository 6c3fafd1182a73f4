// MainWindow: what the viewport grid's viewports share with the MPR layout (the series'
// measurements, curved MPR, the measurement list following the active viewport) and the
// RECIST follow-up dock, whose lesions open in the grid.
#include "ui/app/MainWindow.h"

#include <QDockWidget>
#include <QStatusBar>

#include "core/store/StudyStore.h"
#include "ui/app/MeasurementControls.h"
#include "ui/followup/FollowUpPanel.h"
#include "ui/mpr/MeasurementAutosave.h"
#include "ui/mpr/MeasurementList.h"
#include "ui/mpr/SeriesMeasurements.h"
#include "ui/mpr/SliceView.h"
#include "ui/viewports/SeriesSession.h"
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
    auto* dock = new QDockWidget(tr("Follow-up (RECIST 1.1)"), this);
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

void MainWindow::wireViewports() {
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
