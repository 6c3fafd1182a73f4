// Measuring in the workstation window on the demo head CT, driven by the mouse and
// the keys: the tool bar and its keys, undo and redo of every edit (add, a handle
// moved, rename, delete, clear) with Edit's texts following, the measurement list
// (rows, a click that moves the views, rename, Del, read-only rows), measurements
// kept per series, and Help > Keyboard Shortcuts. Offscreen.
#include <QAction>
#include <QApplication>
#include <QDockWidget>
#include <QHeaderView>
#include <QLineEdit>
#include <QMenu>
#include <QMenuBar>
#include <QPushButton>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTabBar>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>
#include <QToolBar>
#include <QWheelEvent>

#include <cmath>
#include <memory>

#include "tests/support/OffscreenPlatform.h"
#include "ui/app/MainWindow.h"
#include "ui/app/MeasurementControls.h"
#include "ui/app/ShortcutsDialog.h"
#include "ui/app/ViewLayout.h"
#include "ui/mpr/MeasurementList.h"
#include "ui/mpr/MeasurementPainter.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SeriesMeasurements.h"
#include "ui/mpr/SliceView.h"

using namespace lucent;

namespace {

const QString kDemoCt = QStringLiteral("/usr/share/doc/invesalius-examples/examples/Cranium.inv3");

void drag(QWidget* w, QPoint from, QPoint to) {
    QTest::mousePress(w, Qt::LeftButton, Qt::NoModifier, from);
    QTest::mouseMove(w, (from + to) / 2);
    QTest::mouseMove(w, to);
    QTest::mouseRelease(w, Qt::LeftButton, Qt::NoModifier, to);
}

QString plain(QString text) {
    return text.remove('&');
}

} // namespace

class TestMeasurementPanel : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void init();
    void cleanup();
    void toolBarPicksOneToolForEveryView();
    void undoAndRedoEveryEdit();
    void listClickMovesTheViews();
    void readOnlyRowsAreGreyAndLocked();
    void arrowTextIsTypedAndEdited();
    void aDrawingToolKeepsTheDoubleClick();
    void measurementsStayWithTheirSeries();
    void shortcutsDialogListsEveryKey();

private:
    SliceView* axial() const { return window_->view(Orientation::Axial); }
    SeriesMeasurements* measurements() const { return window_->measurements(); }
    MeasurementList* list() const { return window_->measurementControls()->list(); }
    QTableWidget* table() const { return list()->table(); }
    QAction* undo() const { return window_->measurementControls()->undoAction(); }
    QAction* redo() const { return window_->measurementControls()->redoAction(); }
    QAction* editAction(const QString& text) const;
    void keys(QKeyCombination combination) {
        QTest::keyClick(window_.get(), combination.key(), combination.keyboardModifiers());
    }
    void clickRow(int row);
    double firstLength() const { return measurementLengthMm(measurements()->measurements()[0]); }
    void openDemoCt();

    QTemporaryDir settingsDir_;
    std::unique_ptr<MainWindow> window_;
};

void TestMeasurementPanel::initTestCase() {
    if (!QFileInfo::exists(kDemoCt)) {
        QSKIP("the demo CT (Debian package invesalius-examples) is not installed");
    }
    QVERIFY(settingsDir_.isValid());
    // Settings of a test-only application in a temporary folder, never the user's.
    QStandardPaths::setTestModeEnabled(true);
    QCoreApplication::setOrganizationName(QStringLiteral("lucent-test"));
    QCoreApplication::setApplicationName(QStringLiteral("test_measurement_panel"));
    QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, settingsDir_.path());
}

void TestMeasurementPanel::openDemoCt() {
    QSignalSpy finished(window_.get(), &MainWindow::loadFinished);
    window_->openPath(kDemoCt);
    QTRY_COMPARE_WITH_TIMEOUT(finished.count(), 1, 30000);
    QVERIFY(finished.at(0).at(0).toBool());
    // A slow load shows a progress dialog: the shortcuts want the window active again.
    window_->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(window_.get()));
}

void TestMeasurementPanel::init() {
    window_ = std::make_unique<MainWindow>();
    window_->resize(1600, 1000);
    window_->show();
    window_->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(window_.get()));
    keys(Qt::CTRL | Qt::Key_2); // 1 x 3: the MPR views only
    window_->findChild<QDockWidget*>(QStringLiteral("volumeDock"))->hide();
    openDemoCt();
    QVERIFY(measurements() != nullptr);
    QVERIFY2(axial()->width() > 250 && axial()->height() > 250,
             qPrintable(QStringLiteral("%1 x %2").arg(axial()->width()).arg(axial()->height())));
}

void TestMeasurementPanel::cleanup() {
    window_.reset();
}

QAction* TestMeasurementPanel::editAction(const QString& text) const {
    for (QAction* menu : window_->menuBar()->actions()) {
        if (plain(menu->text()) == QStringLiteral("Edit")) {
            for (QAction* a : menu->menu()->actions()) {
                if (plain(a->text()) == text) {
                    return a;
                }
            }
        }
    }
    return nullptr;
}

void TestMeasurementPanel::clickRow(int row) {
    const QRect cell = table()->visualItemRect(table()->item(row, MeasurementList::Value));
    QTest::mouseClick(table()->viewport(), Qt::LeftButton, Qt::NoModifier, cell.center());
}

void TestMeasurementPanel::toolBarPicksOneToolForEveryView() {
    auto* bar = window_->findChild<QToolBar*>(QStringLiteral("toolsToolBar"));
    QVERIFY(bar != nullptr && bar->isVisible());
    MeasurementControls* controls = window_->measurementControls();
    int checked = 0;
    for (const SliceToolInfo& info : sliceTools()) {
        QAction* a = controls->toolAction(info.tool);
        QVERIFY(a != nullptr && bar->actions().contains(a) && a->isCheckable());
        QVERIFY2(a->toolTip().endsWith(QStringLiteral("(%1)").arg(QLatin1String(info.key))),
                 qPrintable(a->toolTip()));
        checked += a->isChecked() ? 1 : 0;
    }
    QCOMPARE(checked, 1);
    QVERIFY(controls->toolAction(SliceTool::Crosshair)->isChecked());
    // The list is a tab beside the 3D controls; a measuring tool brings it to the front.
    auto* volumeDock = window_->findChild<QDockWidget*>(QStringLiteral("volumeDock"));
    auto* listDock = window_->findChild<QDockWidget*>(QStringLiteral("measurementDock"));
    volumeDock->show(); // back from init(), which hid it for room
    QVERIFY(window_->tabifiedDockWidgets(listDock).contains(volumeDock));
    auto frontTab = [this] {
        for (const QTabBar* tabs : window_->findChildren<QTabBar*>()) {
            for (int t = 0; t < tabs->count(); ++t) {
                if (tabs->tabText(t) == QStringLiteral("Measurements")) {
                    return tabs->tabText(tabs->currentIndex());
                }
            }
        }
        return QString();
    };
    volumeDock->raise();
    QTRY_COMPARE(frontTab(), volumeDock->windowTitle());
    controls->toolAction(SliceTool::Ellipse)->trigger();
    QTRY_COMPARE(frontTab(), listDock->windowTitle());
    for (const Orientation o : {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal}) {
        QCOMPARE(window_->view(o)->tool(), SliceTool::Ellipse);
    }
    // A key in one view: every view and the tool bar follow.
    QTest::keyClick(window_->view(Orientation::Coronal), Qt::Key_K);
    QVERIFY(controls->toolAction(SliceTool::CobbAngle)->isChecked());
    QVERIFY(!controls->toolAction(SliceTool::Ellipse)->isChecked());
    QCOMPARE(axial()->tool(), SliceTool::CobbAngle);
    // The view's context menu is made from the same table.
    QMenu menu;
    axial()->fillContextMenu(menu);
    QStringList texts;
    for (const QAction* a : menu.actions()) {
        texts << a->text();
    }
    for (const SliceToolInfo& info : sliceTools()) {
        QVERIFY2(texts.contains(QStringLiteral("%1\t%2").arg(QLatin1String(info.name),
                                                             QLatin1String(info.key))),
                 info.name);
    }
}

void TestMeasurementPanel::undoAndRedoEveryEdit() {
    SliceView* view = axial();
    const double ps = view->plane().pixelSize;
    QVERIFY(!undo()->isEnabled() && !redo()->isEnabled());
    QCOMPARE(undo()->text(), QStringLiteral("Undo"));

    // Add: a distance of 100 pixels, then an angle, with the mouse.
    window_->measurementControls()->toolAction(SliceTool::Distance)->trigger();
    drag(view, {60, 80}, {160, 80});
    QCOMPARE(table()->rowCount(), 1);
    QCOMPARE(undo()->text(), QStringLiteral("Undo Add distance"));
    QVERIFY(undo()->isEnabled());
    QCOMPARE(table()->item(0, MeasurementList::Kind)->text(), QStringLiteral("Distance"));
    QCOMPARE(table()->item(0, MeasurementList::Value)->text(),
             QStringLiteral("%1 mm").arg(100.0 * ps, 0, 'f', 1));
    keys(Qt::CTRL | Qt::Key_Z);
    QCOMPARE(table()->rowCount(), 0);
    QVERIFY(!undo()->isEnabled());
    QCOMPARE(redo()->text(), QStringLiteral("Redo Add distance"));
    keys(Qt::CTRL | Qt::SHIFT | Qt::Key_Z);
    QCOMPARE(table()->rowCount(), 1);
    QVERIFY(std::abs(firstLength() - 100.0 * ps) < 1e-6);
    QTest::keyClick(view, Qt::Key_A);
    drag(view, {60, 200}, {120, 200});
    QTest::mouseClick(view, Qt::LeftButton, Qt::NoModifier, {120, 140});
    QCOMPARE(table()->rowCount(), 2);
    QCOMPARE(undo()->text(), QStringLiteral("Undo Add angle"));

    // Move a handle: the distance's right end 40 pixels down.
    drag(view, {160, 80}, {160, 120});
    const double moved = std::hypot(100.0, 40.0) * ps;
    QVERIFY(std::abs(firstLength() - moved) < 1e-6);
    QCOMPARE(undo()->text(), QStringLiteral("Undo Change distance"));
    keys(Qt::CTRL | Qt::Key_Z);
    QVERIFY(std::abs(firstLength() - 100.0 * ps) < 1e-6);
    QCOMPARE(table()->item(0, MeasurementList::Value)->text(),
             QStringLiteral("%1 mm").arg(100.0 * ps, 0, 'f', 1));
    keys(Qt::CTRL | Qt::Key_Y);
    QVERIFY(std::abs(firstLength() - moved) < 1e-6);

    // Rename: the name cell edited in the list.
    table()->setFocus();
    table()->editItem(table()->item(0, MeasurementList::Name));
    auto* editor = qobject_cast<QLineEdit*>(QApplication::focusWidget());
    QVERIFY(editor != nullptr);
    QTest::keyClicks(editor, QStringLiteral("Lesion 1"));
    QTest::keyClick(editor, Qt::Key_Return);
    QTRY_COMPARE(measurements()->measurements()[0].label, std::string("Lesion 1"));
    QCOMPARE(table()->item(0, MeasurementList::Name)->text(), QStringLiteral("Lesion 1"));
    QCOMPARE(undo()->text(), QStringLiteral("Undo Rename distance"));
    QVERIFY(measurementOverlayText(measurements()->measurements()[0]).startsWith("Lesion 1\n"));
    keys(Qt::CTRL | Qt::Key_Z);
    QCOMPARE(measurements()->measurements()[0].label, std::string());
    QCOMPARE(table()->item(0, MeasurementList::Name)->text(), QString());
    keys(Qt::CTRL | Qt::SHIFT | Qt::Key_Z);
    QCOMPARE(table()->item(0, MeasurementList::Name)->text(), QStringLiteral("Lesion 1"));

    // Delete: the row picked and Del pressed in the list.
    clickRow(0);
    QCOMPARE(measurements()->selected(), measurements()->measurements()[0].id);
    QVERIFY(list()->deleteButton()->isEnabled());
    QTest::keyClick(table(), Qt::Key_Delete);
    QCOMPARE(table()->rowCount(), 1);
    QCOMPARE(table()->item(0, MeasurementList::Kind)->text(), QStringLiteral("Angle"));
    QCOMPARE(undo()->text(), QStringLiteral("Undo Delete distance"));
    keys(Qt::CTRL | Qt::Key_Z);
    QCOMPARE(table()->rowCount(), 2);
    QCOMPARE(table()->item(0, MeasurementList::Name)->text(), QStringLiteral("Lesion 1"));
    keys(Qt::CTRL | Qt::Key_Y);
    QCOMPARE(table()->rowCount(), 1);
    keys(Qt::CTRL | Qt::Key_Z);
    QCOMPARE(table()->rowCount(), 2);

    // Clear: Edit > Clear Measurements.
    QAction* clear = editAction(QStringLiteral("Clear Measurements"));
    QVERIFY(clear != nullptr && clear->isEnabled());
    clear->trigger();
    QCOMPARE(table()->rowCount(), 0);
    QVERIFY(!clear->isEnabled());
    QCOMPARE(undo()->text(), QStringLiteral("Undo Clear measurements"));
    keys(Qt::CTRL | Qt::Key_Z);
    QCOMPARE(table()->rowCount(), 2);
    QVERIFY(std::abs(firstLength() - moved) < 1e-6);
    keys(Qt::CTRL | Qt::SHIFT | Qt::Key_Z);
    QCOMPARE(table()->rowCount(), 0);
    // Back to the start, one step at a time, and forward again.
    int steps = 0;
    while (undo()->isEnabled()) {
        keys(Qt::CTRL | Qt::Key_Z);
        ++steps;
    }
    QCOMPARE(steps, 5); // add, add, change, rename, clear (the delete was undone)
    QCOMPARE(table()->rowCount(), 0);
    while (redo()->isEnabled()) {
        keys(Qt::CTRL | Qt::Key_Y);
    }
    QCOMPARE(table()->rowCount(), 0);
    QCOMPARE(undo()->text(), QStringLiteral("Undo Clear measurements"));
}

void TestMeasurementPanel::listClickMovesTheViews() {
    SliceView* view = axial();
    MprCursor* cursor = window_->cursor();
    const double slice = view->slicePosition();
    QTest::keyClick(view, Qt::Key_D);
    drag(view, {60, 80}, {160, 80});
    QCOMPARE(table()->item(0, MeasurementList::Plane)->text(), QStringLiteral("Axial"));
    const int sliceNumber = window_->volume()->dims().z / 2 + 1;
    QCOMPARE(table()->item(0, MeasurementList::Slice)->text(), QString::number(sliceNumber));
    // Five slices on; the measurement is not drawn there.
    QWheelEvent wheel(QPointF(150, 150), view->mapToGlobal(QPointF(150, 150)), QPoint(),
                      QPoint(0, 5 * 120), Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(view, &wheel);
    QVERIFY(std::abs(view->slicePosition() - slice) > 1.0);
    const Measurement first = measurements()->measurements()[0];
    QVERIFY(!measurementInPlane(first, view->plane(), view->measurementTolerance()));
    clickRow(0);
    QVERIFY(std::abs(view->slicePosition() - slice) < 1e-9);
    QVERIFY(measurementInPlane(first, view->plane(), view->measurementTolerance()));

    // One on an oblique coronal plane (the planes turned by shift-drag on the axial view).
    const glm::dvec2 c = view->plane().pixelOf(cursor->point());
    const QPoint centre(int(std::lround(c.x)), int(std::lround(c.y)));
    QTest::mousePress(view, Qt::LeftButton, Qt::ShiftModifier, centre + QPoint(80, 0));
    QTest::mouseMove(view, centre + QPoint(70, 40));
    QTest::mouseRelease(view, Qt::LeftButton, Qt::ShiftModifier, centre + QPoint(70, 40));
    SliceView* coronal = window_->view(Orientation::Coronal);
    drag(coronal, {60, 100}, {160, 130});
    QCOMPARE(table()->rowCount(), 2);
    QCOMPARE(table()->item(1, MeasurementList::Plane)->text(), QStringLiteral("Oblique"));
    QCOMPARE(table()->item(1, MeasurementList::Slice)->text(), QString());
    const Measurement oblique = measurements()->measurements()[1];
    QTest::keyClick(coronal, Qt::Key_O); // standard planes again
    QVERIFY(!measurementInPlane(oblique, coronal->plane(), coronal->measurementTolerance()));
    clickRow(1);
    QCOMPARE(measurements()->selected(), oblique.id);
    QVERIFY(measurementInPlane(oblique, coronal->plane(), coronal->measurementTolerance()));
    QVERIFY(distanceFromPlane(oblique, coronal->plane()) < 1e-6);
}

void TestMeasurementPanel::readOnlyRowsAreGreyAndLocked() {
    Measurement foreign;
    foreign.kind = MeasurementKind::Distance;
    foreign.plane = axial()->plane();
    foreign.points = {axial()->plane().pointAt(50, 50), axial()->plane().pointAt(150, 50)};
    foreign.label = "From PACS";
    foreign.readOnly = true;
    measurements()->load({foreign});
    QCOMPARE(table()->rowCount(), 1);
    QTableWidgetItem* name = table()->item(0, MeasurementList::Name);
    QVERIFY(!(name->flags() & Qt::ItemIsEditable));
    QCOMPARE(name->foreground().color(),
             table()->palette().color(QPalette::Disabled, QPalette::Text));
    clickRow(0);
    QVERIFY(!list()->deleteButton()->isEnabled());
    QTest::keyClick(table(), Qt::Key_Delete);
    QCOMPARE(table()->rowCount(), 1);
    QVERIFY(!editAction(QStringLiteral("Delete Measurement"))->isEnabled());
    QVERIFY(!undo()->isEnabled()); // a load is not an edit
}

void TestMeasurementPanel::arrowTextIsTypedAndEdited() {
    window_->measurementControls()->toolAction(SliceTool::Arrow)->trigger();
    drag(axial(), {100, 100}, {160, 60});
    QLineEdit* editor = axial()->measurementTools().textEditor();
    QVERIFY(editor != nullptr);
    QTest::keyClicks(editor, QStringLiteral("Cyst"));
    QTest::keyClick(editor, Qt::Key_Return);
    QCOMPARE(table()->rowCount(), 1);
    QCOMPARE(table()->item(0, MeasurementList::Value)->text(), QStringLiteral("Cyst"));
    QCOMPARE(undo()->text(), QStringLiteral("Undo Add arrow"));
    // Its text edited in the list's value cell: one Change.
    table()->setFocus();
    table()->editItem(table()->item(0, MeasurementList::Value));
    auto* cell = qobject_cast<QLineEdit*>(QApplication::focusWidget());
    QVERIFY(cell != nullptr);
    cell->selectAll();
    QTest::keyClicks(cell, QStringLiteral("Simple cyst"));
    QTest::keyClick(cell, Qt::Key_Return);
    QTRY_COMPARE(measurements()->measurements()[0].text, std::string("Simple cyst"));
    QCOMPARE(undo()->text(), QStringLiteral("Undo Change arrow"));
    keys(Qt::CTRL | Qt::Key_Z);
    QCOMPARE(table()->item(0, MeasurementList::Value)->text(), QStringLiteral("Cyst"));
}

void TestMeasurementPanel::aDrawingToolKeepsTheDoubleClick() {
    ViewLayout* layout = window_->viewLayout();
    QCOMPARE(layout->arrangement(), ViewLayout::Arrangement::Row1x3);
    // Quick clicks of the angle tool are its points, not a maximize.
    QTest::keyClick(axial(), Qt::Key_A);
    QTest::mouseDClick(axial(), Qt::LeftButton, Qt::NoModifier, {100, 100});
    QCOMPARE(layout->arrangement(), ViewLayout::Arrangement::Row1x3);
    QVERIFY(axial()->measurementTools().busy());
    // With the crosshair a double-click maximizes, as before.
    QTest::keyClick(axial(), Qt::Key_Escape); // drops the angle
    QTest::keyClick(axial(), Qt::Key_Escape); // the crosshair tool
    QCOMPARE(axial()->tool(), SliceTool::Crosshair);
    QTest::mouseDClick(axial(), Qt::LeftButton, Qt::NoModifier, {100, 100});
    QCOMPARE(layout->arrangement(), ViewLayout::Arrangement::Single);
}

void TestMeasurementPanel::measurementsStayWithTheirSeries() {
    SeriesMeasurements* first = measurements();
    QCOMPARE(first->seriesUid(), window_->volume()->seriesUid);
    QTest::keyClick(axial(), Qt::Key_D);
    drag(axial(), {60, 80}, {160, 80});
    QSignalSpy opened(window_.get(), &MainWindow::measurementsOpened);
    QSignalSpy changed(first, &SeriesMeasurements::changed);
    openDemoCt(); // the same series again: its measurements come back with it
    QCOMPARE(measurements(), first);
    QCOMPARE(opened.count(), 0);
    QCOMPARE(table()->rowCount(), 1);
    QTest::keyClick(axial(), Qt::Key_Delete); // the selected one: the last drawn
    QCOMPARE(table()->rowCount(), 0);
    QCOMPARE(changed.count(), 1);
}

void TestMeasurementPanel::shortcutsDialogListsEveryKey() {
    QAction* help = nullptr;
    for (QAction* menu : window_->menuBar()->actions()) {
        if (plain(menu->text()) == QStringLiteral("Help")) {
            help = menu->menu()->actions().value(0);
        }
    }
    QVERIFY(help != nullptr);
    QCOMPARE(plain(help->text()), QStringLiteral("Keyboard Shortcuts..."));
    help->trigger();
    auto* dialog = window_->findChild<ShortcutsDialog*>(QStringLiteral("shortcutsDialog"));
    QVERIFY(dialog != nullptr && dialog->isVisible());
    QTableWidget* rows = dialog->table();
    auto has = [rows](const QString& keys, const QString& what) {
        for (int r = 0; r < rows->rowCount(); ++r) {
            if (rows->item(r, 1)->text() == keys && rows->item(r, 2)->text().contains(what)) {
                return true;
            }
        }
        return false;
    };
    for (const SliceToolInfo& info : sliceTools()) {
        QVERIFY2(has(QLatin1String(info.key), QLatin1String(info.name)), info.name);
    }
    for (const SliceKeyInfo& key : sliceViewKeys()) {
        QVERIFY2(has(QLatin1String(key.keys), QLatin1String(key.what)), key.keys);
    }
    QVERIFY(has(QKeySequence(QKeySequence::Undo).toString(QKeySequence::NativeText),
                QStringLiteral("Undo")));
    QVERIFY(has(QStringLiteral("Ctrl+Shift+Z, Ctrl+Y"), QStringLiteral("Redo")));
    QVERIFY(has(QStringLiteral("Ctrl+2"), QStringLiteral("1 x 3")));
    QVERIFY(has(QStringLiteral("Ctrl+Shift+O"), QStringLiteral("Open Folder")));
}

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestMeasurementPanel test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_measurement_panel.moc"
