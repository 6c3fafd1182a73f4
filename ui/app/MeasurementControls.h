#pragma once

#include <array>

#include <QObject>
#include <QPointer>

#include "ui/mpr/SeriesMeasurements.h"
#include "ui/mpr/SliceTools.h"

class QAction;
class QActionGroup;
class QDockWidget;
class QMainWindow;
class QMenu;
class QToolBar;

namespace lucent {

class MeasurementList;
class MprCursor;
class SliceView;

// The main window's measuring: the tool bar (one checkable action per sliceTools()
// row, the key in its tooltip, one tool active in every MPR view), Undo, Redo,
// Delete and Clear in the Edit menu (text and enabled state following the series'
// document), and the measurement list in a dock ("measurementDock", a tab beside the
// 3D controls, raised when a measuring tool is picked). All of them act on the series
// shown now (setMeasurements).
class MeasurementControls : public QObject {
    Q_OBJECT

public:
    MeasurementControls(QMainWindow* window, MprCursor* cursor,
                        const std::array<SliceView*, 3>& views, QMenu* editMenu);

    void setMeasurements(SeriesMeasurements* measurements);

    QToolBar* toolBar() const { return toolBar_; }
    QAction* toolAction(SliceTool tool) const;
    QAction* undoAction() const { return undo_; }
    QAction* redoAction() const { return redo_; }
    MeasurementList* list() const { return list_; }

private:
    void setTool(SliceTool tool);
    void updateActions();

    std::array<SliceView*, 3> views_;
    QPointer<SeriesMeasurements> measurements_;
    QToolBar* toolBar_;
    QActionGroup* tools_;
    QAction* undo_;
    QAction* redo_;
    QAction* delete_;
    QAction* clear_;
    MeasurementList* list_;
    QDockWidget* dock_ = nullptr;
};

} // namespace lucent
