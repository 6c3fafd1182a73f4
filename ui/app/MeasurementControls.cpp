#include "ui/app/MeasurementControls.h"

#include <QActionGroup>
#include <QDockWidget>
#include <QMainWindow>
#include <QMenu>
#include <QToolBar>

#include "ui/mpr/MeasurementList.h"
#include "ui/mpr/SliceView.h"

namespace lucent {

MeasurementControls::MeasurementControls(QMainWindow* window, MprCursor* cursor,
                                         const std::array<SliceView*, 3>& views, QMenu* editMenu)
    : QObject(window), views_(views), toolBar_(new QToolBar(tr("Tools"), window)),
      tools_(new QActionGroup(this)), list_(new MeasurementList(cursor)) {
    toolBar_->setObjectName(QStringLiteral("toolsToolBar"));
    toolBar_->setToolButtonStyle(Qt::ToolButtonTextOnly);
    window->addToolBar(Qt::TopToolBarArea, toolBar_);
    tools_->setExclusive(true);
    for (const SliceToolInfo& info : sliceTools()) {
        QAction* action = toolBar_->addAction(QString::fromLatin1(info.name));
        action->setCheckable(true);
        action->setChecked(info.tool == views_[0]->tool());
        action->setToolTip(sliceToolToolTip(info));
        action->setStatusTip(QString::fromLatin1(info.help));
        action->setData(static_cast<int>(info.tool));
        tools_->addAction(action);
        const SliceTool tool = info.tool;
        connect(action, &QAction::triggered, this, [this, tool] { setTool(tool); });
    }
    // A key pressed in one view picks the tool for all of them and the tool bar.
    for (SliceView* view : views_) {
        connect(view, &SliceView::toolChanged, this, &MeasurementControls::setTool);
    }

    undo_ = editMenu->addAction(tr("Undo"));
    undo_->setShortcut(QKeySequence::Undo);
    connect(undo_, &QAction::triggered, this, [this] {
        if (measurements_ != nullptr) {
            measurements_->undo();
        }
    });
    redo_ = editMenu->addAction(tr("Redo"));
    redo_->setShortcuts({QKeySequence(tr("Ctrl+Shift+Z")), QKeySequence(tr("Ctrl+Y"))});
    connect(redo_, &QAction::triggered, this, [this] {
        if (measurements_ != nullptr) {
            measurements_->redo();
        }
    });
    editMenu->addSeparator();
    delete_ = editMenu->addAction(tr("Delete Measurement"));
    connect(delete_, &QAction::triggered, this, [this] {
        if (measurements_ != nullptr) {
            measurements_->remove(measurements_->selected());
        }
    });
    clear_ = editMenu->addAction(tr("Clear Measurements"));
    connect(clear_, &QAction::triggered, this, [this] {
        if (measurements_ != nullptr) {
            measurements_->clear();
        }
    });
    toolBar_->addSeparator();
    toolBar_->addAction(undo_);
    toolBar_->addAction(redo_);

    auto* dock = new QDockWidget(tr("Measurements"), window);
    dock->setObjectName(QStringLiteral("measurementDock"));
    dock->setWidget(list_);
    // Beside the views, as OHIF and Weasis show their lists: a tab of the right dock
    // (with the 3D controls, when they are there), raised when a measuring tool is picked.
    window->addDockWidget(Qt::RightDockWidgetArea, dock);
    if (auto* volumeDock = window->findChild<QDockWidget*>(QStringLiteral("volumeDock"))) {
        window->tabifyDockWidget(volumeDock, dock);
        volumeDock->raise();
    }
    dock_ = dock;
    updateActions();
}

QAction* MeasurementControls::toolAction(SliceTool tool) const {
    for (QAction* action : tools_->actions()) {
        if (action->data().toInt() == static_cast<int>(tool)) {
            return action;
        }
    }
    return nullptr;
}

void MeasurementControls::setTool(SliceTool tool) {
    for (SliceView* view : views_) {
        view->setTool(tool); // says toolChanged only when it changes: no loop
    }
    if (QAction* action = toolAction(tool)) {
        action->setChecked(true);
    }
    // Not a dock the reader closed; one behind the 3D controls' tab comes to the front.
    if (sliceToolInfo(tool).kind.has_value() && dock_->toggleViewAction()->isChecked()) {
        dock_->raise();
    }
}

void MeasurementControls::setMeasurements(SeriesMeasurements* measurements) {
    if (measurements_ != nullptr) {
        disconnect(measurements_, nullptr, this, nullptr);
    }
    measurements_ = measurements;
    for (SliceView* view : views_) {
        view->setMeasurements(measurements);
    }
    list_->setMeasurements(measurements);
    if (measurements != nullptr) {
        connect(measurements, &SeriesMeasurements::changed, this,
                &MeasurementControls::updateActions);
        connect(measurements, &SeriesMeasurements::selectionChanged, this,
                &MeasurementControls::updateActions);
    }
    updateActions();
}

void MeasurementControls::updateActions() {
    const SeriesMeasurements* m = measurements_;
    const MeasurementDocument* doc = m != nullptr ? &m->document() : nullptr;
    auto described = [](const QString& verb, const std::string& what) {
        return what.empty() ? verb : verb + ' ' + QString::fromStdString(what);
    };
    undo_->setEnabled(doc != nullptr && doc->canUndo());
    redo_->setEnabled(doc != nullptr && doc->canRedo());
    undo_->setText(described(tr("Undo"), doc != nullptr ? doc->undoText() : std::string()));
    redo_->setText(described(tr("Redo"), doc != nullptr ? doc->redoText() : std::string()));
    undo_->setToolTip(undo_->text() + QStringLiteral(" (Ctrl+Z)"));
    redo_->setToolTip(redo_->text() + QStringLiteral(" (Ctrl+Shift+Z)"));
    const Measurement* selected = m != nullptr ? m->find(m->selected()) : nullptr;
    delete_->setEnabled(selected != nullptr && !selected->readOnly);
    clear_->setEnabled(doc != nullptr && !doc->measurements().empty());
}

} // namespace lucent
