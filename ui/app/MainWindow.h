#pragma once

#include <array>
#include <map>
#include <memory>
#include <string>

#include <QMainWindow>

#include "core/mpr/PlaneSampler.h"
#include "core/volume/Volume.h"

class QActionGroup;
class QLabel;
class QStackedWidget;

namespace lucent {

class CurvedMprView;
class FollowUpPanel;
class Viewport;
struct LesionLocation;
class MeasurementAutosave;
class MeasurementControls;
class MovieExportDialog;
class MprCursor;
class SeriesMeasurements;
class ShortcutsDialog;
class SliceView;
class TransferFunctionEditor;
class ViewLayout;
class ViewportWorkspace;
class StudyHanging;
class PriorsForStudy;
class PriorTimeline;
class FusionPanel;
class ViewportFusion;
class SegmentEditor;
class SegmentsPanel;
class SegmentationAutosave;
class SegmentTools3d;
class PacsService;
class VolumeLoader;
class VolumeView;

// The workstation window: axial, coronal and sagittal views and the 3D view in a
// ViewLayout (2x2, 1x3, 1x1; View menu, Ctrl+1/2/3), linked through one crosshair
// and window, a status bar describing the volume, the series opened in this
// session in a dock (StudyBrowser, "studyDock"), screenshots (File menu) and
// settings that persist (QSettings of the application: layout, last folder,
// window geometry and dock state; restored by the constructor, saved on close),
// and the look: the saved theme (dark by default; View > Theme) is applied to
// the application by the constructor.
// Measuring (MeasurementControls): a tool bar of the MPR tools, Edit > Undo/Redo,
// the measurement list dock, Help > Keyboard Shortcuts; each series opened keeps
// its measurements (SeriesMeasurements, by series UID) for the session.
class MainWindow : public QMainWindow {
    Q_OBJECT

public:
    explicit MainWindow(QWidget* parent = nullptr);
    ~MainWindow() override;

    // Loads a DICOM folder/file/DICOMDIR, .mhd, .nii(.gz) or .inv3 with VolumeLoader
    // (worker thread, progress with cancel, errors in a dialog with details);
    // series picks one (id or UID). A load still running is cancelled.
    void openPath(const QString& path, const QString& series = {});
    // Opens a study (a folder, DICOMDIR or store folder) as a radiologist reads it: the
    // best hanging protocol for it and the patient's priors (StudyHanging) in the grid,
    // the comparable prior fetched from PACS when the protocol asks for one.
    void openStudy(const QString& path);
    StudyHanging* hanging() const { return hanging_; }
    void setVolume(std::shared_ptr<const Volume> volume);
    const std::shared_ptr<const Volume>& volume() const { return volume_; }

    SliceView* view(Orientation orientation) const;
    VolumeView* volumeView() const { return volumeView_; }
    ViewLayout* viewLayout() const { return layout_; }
    // The multi-series viewport grid (View > Viewport Grid), in place of the MPR
    // layout of one series while it is shown.
    ViewportWorkspace* workspace() const { return workspace_; }
    bool workspaceShown() const;
    // Shows the viewport grid (true) or the MPR layout of the series opened last.
    void showWorkspace(bool shown);
    MprCursor* cursor() const { return cursor_; }
    // The curved MPR window of the last path drawn (P on an MPR view); nullptr before.
    CurvedMprView* curvedMpr() const { return curvedMpr_; }
    // The measurements of the series shown now (nullptr before one is open) and the
    // tool bar, Edit actions and list that act on them.
    SeriesMeasurements* measurements() const { return measurements_; }
    MeasurementControls* measurementControls() const { return measurementControls_; }
    // Keeps the measurements of stored series as DICOM SR in the study store.
    MeasurementAutosave* measurementAutosave() const { return autosave_; }
    // The measurements of a series: the same object for every view of it, made (and
    // announced by measurementsOpened) the first time; nullptr for no volume.
    SeriesMeasurements* measurementsFor(const std::shared_ptr<const Volume>& volume);
    // The RECIST follow-up of the patient shown (a dock).
    FollowUpPanel* followUp() const { return followUp_; }
    PriorTimeline* priorTimeline() const { return priorTimeline_; }
    // The Fusion dock and what it drives: a second series over the active viewport's.
    FusionPanel* fusionPanel() const { return fusionPanel_; }
    ViewportFusion* viewportFusion() const { return fusion_; }
    // The Segments dock and the Segment Editor it drives over the grid's MPR views
    // (segmentEditor()->sessions(): the segments of each series, for the SEG autosave).
    SegmentsPanel* segmentsPanel() const { return segmentsPanel_; }
    SegmentEditor* segmentEditor() const { return segmentEditor_; }
    SegmentTools3d* segmentTools3d() const { return segmentTools3d_; }
    // Help > Keyboard Shortcuts: opens (or raises) the dialog and returns it.
    ShortcutsDialog* showShortcuts();

    enum class ScreenshotScope { ActiveView, Layout };
    // Writes a PNG of the active view or of the whole view area; on failure
    // returns false with the reason in error.
    bool saveScreenshot(const QString& file, ScreenshotScope scope, QString* error = nullptr);

    // File > Export Movie: opens the (non-modal) dialog on the 3D view's scene and
    // the MPR window, or returns nullptr with a status message when no volume is open.
    MovieExportDialog* openMovieExport();

    // The folder of the last path opened (settings key "files/lastFolder").
    const QString& lastFolder() const { return lastFolder_; }
    void saveSettings() const;
    void restoreSettings();

signals:
    // After every load attempt: ok is false on error or cancel.
    void loadFinished(bool ok);
    // A series' measurements were made, the first time that series is shown: where
    // persistence loads what was saved for it and connects to its changed().
    void measurementsOpened(lucent::SeriesMeasurements* measurements);

protected:
    void closeEvent(QCloseEvent* event) override;

private:
    void addViewMenu();
    void openFolderDialog();
    void openFileDialog();
    void screenshotDialog(ScreenshotScope scope);
    void openCurvedMpr(const std::shared_ptr<const Volume>& volume,
                       const std::vector<glm::dvec3>& points, const glm::dvec3& up);
    void showMeasurementsOf(const std::shared_ptr<const Volume>& volume);
    // MainWindowViewports.cpp: the viewport grid's tools, the follow-up dock.
    void wireViewports(PacsService* service);
    void addHangingMenu(QMenu* menu);
    void addFollowUpDock(const QString& storeFolder);
    void addPriorsDock(PriorsForStudy& priors);
    void addFusionDock();
    void addSegmentsDock();
    // The 3D view showing the series: a grid viewport's, else the main page's; nullptr.
    VolumeView* volumeViewOf(const Volume& series) const;
    void viewportContentChanged(Viewport* viewport);
    void goToLesion(const std::vector<LesionLocation>& where);

    MprCursor* cursor_;
    std::array<SliceView*, 3> views_{};
    VolumeView* volumeView_ = nullptr;
    ViewLayout* layout_ = nullptr;
    ViewportWorkspace* workspace_ = nullptr;
    QStackedWidget* central_ = nullptr;
    QActionGroup* layoutActions_ = nullptr;
    TransferFunctionEditor* tfEditor_ = nullptr;
    QLabel* info_;
    VolumeLoader* loader_ = nullptr;
    QString lastFolder_;
    std::shared_ptr<const Volume> volume_;
    CurvedMprView* curvedMpr_ = nullptr;
    MeasurementControls* measurementControls_ = nullptr;
    std::map<std::string, SeriesMeasurements*> seriesMeasurements_; // by series UID
    SeriesMeasurements* measurements_ = nullptr;
    MeasurementAutosave* autosave_ = nullptr;
    ShortcutsDialog* shortcuts_ = nullptr;
    FollowUpPanel* followUp_ = nullptr;
    PriorTimeline* priorTimeline_ = nullptr;
    FusionPanel* fusionPanel_ = nullptr;
    ViewportFusion* fusion_ = nullptr;
    SegmentEditor* segmentEditor_ = nullptr;
    SegmentsPanel* segmentsPanel_ = nullptr;
    SegmentationAutosave* segmentAutosave_ = nullptr;
    SegmentTools3d* segmentTools3d_ = nullptr;
    StudyHanging* hanging_ = nullptr;
    QString storeFolder_;
};

} // namespace lucent
