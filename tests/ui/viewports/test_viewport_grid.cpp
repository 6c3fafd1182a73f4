// The viewport grid: two studies of one patient side by side (1x2), a series dragged
// from the study browser into a viewport, scrolling linked through "link here", the
// pixels of the linked viewport, reference lines, layouts. Real CT; offscreen.
#include <QAbstractItemModel>
#include <QApplication>
#include <QDropEvent>
#include <QMimeData>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <QTreeWidget>
#include <QWheelEvent>

#include <cmath>
#include <memory>

#include "core/io/Catalog.h"
#include "core/store/StudyStore.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/PriorStudy.h"
#include "tests/support/RealData.h"
#include "ui/app/MainWindow.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/ReferenceLines.h"
#include "ui/mpr/SliceView.h"
#include "ui/study/StudyBrowser.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportLinks.h"
#include "ui/viewports/ViewportRegistration.h"
#include "ui/viewports/ViewportWorkspace.h"

using namespace lucent;

namespace {

const char* kCurrent = "dcm_qa_ct/Philips_S21570/S2020";     // 140 x 1 mm
const char* kPriorSource = "dcm_qa_ct/Philips_S21570/S2010"; // the same phantom, 28 x 5 mm
const glm::dvec3 kShift(7.5, -4.0, 12.25); // where the prior's scanner put the same anatomy

// Scrolls `view` by whole wheel notches (positive: deeper).
void scroll(SliceView* view, int notches) {
    const QPointF at(view->width() / 2.0, view->height() / 2.0);
    QWheelEvent wheel(at, view->mapToGlobal(at), QPoint(), QPoint(0, 120 * notches), Qt::NoButton,
                      Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(view, &wheel);
}

// Drops mime data on a widget as a drag from the study browser ends there.
void drop(QWidget* target, const QMimeData* data) {
    const QPoint at(target->width() / 2, target->height() / 2);
    QDragEnterEvent enter(at, Qt::CopyAction, data, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(target, &enter);
    QVERIFY(enter.isAccepted());
    QDropEvent dropped(QPointF(at), Qt::CopyAction, data, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(target, &dropped);
    QVERIFY(dropped.isAccepted());
}

int differingPixels(const QImage& a, const QImage& b) {
    if (a.size() != b.size()) {
        return a.width() * a.height();
    }
    const QImage ga = a.convertToFormat(QImage::Format_Grayscale8);
    const QImage gb = b.convertToFormat(QImage::Format_Grayscale8);
    int n = 0;
    for (int y = 0; y < ga.height(); ++y) {
        for (int x = 0; x < ga.width(); ++x) {
            n += std::abs(ga.constScanLine(y)[x] - gb.constScanLine(y)[x]) > 1 ? 1 : 0;
        }
    }
    return n;
}

} // namespace

class TestViewportGrid : public QObject {
    Q_OBJECT

private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);
        QCoreApplication::setOrganizationName(QStringLiteral("lucent-test"));
        QCoreApplication::setApplicationName(QStringLiteral("test_viewport_grid"));
        QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, settings_.path());
        QSettings().clear();
    }

    void shapesIncludeAsymmetricOnes() {
        ViewportGrid grid;
        for (const char* name : {"1x1", "1x2", "2x2", "3x3", "4x4", "1+2", "2+1"}) {
            const auto shape = gridShape(QString::fromLatin1(name));
            QVERIFY2(shape.has_value(), name);
            grid.setShape(*shape);
            QCOMPARE(grid.count(), static_cast<int>(shape->cells.size()));
        }
        QCOMPARE(gridShape(QStringLiteral("4x4"))->cells.size(), std::size_t{16});
        // 1+2: the first viewport spans both rows on the left.
        const GridShape onePlusTwo = *gridShape(QStringLiteral("1+2"));
        QCOMPARE(onePlusTwo.cells.size(), std::size_t{3});
        QCOMPARE(onePlusTwo.cells[0].rowSpan, 2);
        QVERIFY(!gridShape(QStringLiteral("5x5")).has_value());
    }

    void referenceLineOfACoronalPlaneOnAnAxialOne() {
        VolumeGeometry g;
        g.dims = {100, 100, 100};
        const SlicePlane axial = standardPlane(g, Orientation::Axial, {50, 50, 50}, 100, 100);
        ReferencePlane coronal{{0.0, 30.0, 0.0}, {0.0, 1.0, 0.0}, Qt::yellow, QStringLiteral("2")};
        const auto line = referenceLine(axial, coronal);
        QVERIFY(line.has_value());
        // A coronal plane at y = 30 mm is the row of y = 30 on the axial image.
        QVERIFY(std::abs(line->first.y - axial.pixelOf({50, 30, 50}).y) < 1e-6);
        QVERIFY(std::abs(line->second.y - line->first.y) < 1e-6);
        // A parallel plane cuts nowhere.
        QVERIFY(!referenceLine(axial, {{0, 0, 10}, {0, 0, 1}, Qt::yellow, {}}).has_value());
    }

    void twoStudiesLinkedAfterLinkHere() {
        REQUIRE_DATA(kCurrent);
        QTemporaryDir priorDir;
        QTemporaryDir storeDir;
        const test::PriorStudy prior = test::writePriorStudy(
            test::kRealData / kPriorSource, priorDir.path().toStdString(), "20190101", kShift);
        const QString current = QString::fromStdString((test::kRealData / kCurrent).string());

        MainWindow window;
        window.resize(1200, 700);
        window.show();
        QSignalSpy loaded(&window, &MainWindow::loadFinished);
        window.openPath(current);
        QVERIFY(loaded.wait(60000));
        QVERIFY(loaded.takeFirst().at(0).toBool());

        ViewportWorkspace* workspace = window.workspace();
        workspace->links()->setStoreFolder(storeDir.path());
        workspace->grid()->setShape(*gridShape(QStringLiteral("1x2")));
        window.showWorkspace(true);
        QVERIFY(window.workspaceShown());
        Viewport* left = workspace->grid()->viewport(0);
        Viewport* right = workspace->grid()->viewport(1);
        QVERIFY(left->session() != nullptr); // the series opened, in the first viewport
        QVERIFY(right->session() == nullptr);
        QVERIFY(left->sliceView() != nullptr);

        dropPriorOn(window, right, priorDir.path(), prior);
        if (QTest::currentTestFailed()) {
            return;
        }
        QVERIFY(right->session() != nullptr);
        QCOMPARE(right->session()->volume()->seriesUid, prior.seriesUid);
        QCOMPARE(right->session()->volume()->studyDate, std::string("20190101"));
        QVERIFY(right->sliceView() != nullptr);
        QCoreApplication::processEvents();

        // Linked but in different Frames of Reference: nothing moves, and it says why.
        left->setLinkGroup(1);
        right->setLinkGroup(1);
        SliceView* a = left->sliceView();
        SliceView* b = right->sliceView();
        const glm::dvec3 priorBefore = right->session()->cursor()->point();
        scroll(a, 3);
        QCOMPARE(right->session()->cursor()->point(), priorBefore);
        QVERIFY(workspace->links()->lastNotice().contains(QStringLiteral("not linked")));

        // "Link here": the crosshair on the same anatomy in both.
        const VolumeGeometry& ga = left->session()->volume()->geometry();
        const glm::dvec3 anatomy = ga.toPatient({256.0, 256.0, 70.0});
        right->setLinkGroup(0); // align without moving the other
        left->session()->cursor()->setPoint(anatomy);
        right->session()->cursor()->setPoint(anatomy + kShift);
        right->setLinkGroup(1);
        QCOMPARE(workspace->links()->linkHere(left), 1);
        {
            StudyStore store(storeDir.path().toStdString());
            const auto kept =
                store.seriesOffset(left->session()->volume()->seriesUid, prior.seriesUid);
            QVERIFY(kept.has_value());
            QVERIFY(glm::length(*kept - kShift) < 1e-3);
        }

        // Every scroll lands within half a prior slice of the true position.
        const double half = right->session()->volume()->geometry().spacing.z / 2.0 + 1e-3;
        const QImage before = b->image();
        verifyLinkedScrolls(*left, *right, 12, 4, 3, half, "linked here");
        if (QTest::currentTestFailed()) {
            return;
        }
        QCoreApplication::processEvents();
        verifyPriorSliceShown(*right, before);
        if (QTest::currentTestFailed()) {
            return;
        }

        // "Register" (Ctrl+Alt+R) aligns the pair by itself: its transform (the shift,
        // found from the images) is kept in the store, links the pair before the offset,
        // and every scroll still lands within half a prior slice (plus the 0.5 mm the
        // registration may be off by: the nearest slice may then be the other one).
        registerThePair(*workspace, *left, *right, storeDir.path(), anatomy);
        if (QTest::currentTestFailed()) {
            return;
        }
        verifyLinkedScrolls(*left, *right, 6, -5, -2, half + 0.5, "registered");
        if (QTest::currentTestFailed()) {
            return;
        }

        // Planes that are not parallel do not scroll together, and say why.
        right->show(right->session(), ViewportView::Coronal);
        QCoreApplication::processEvents();
        const glm::dvec3 coronalBefore = right->session()->cursor()->point();
        scroll(left->sliceView(), 2);
        QCOMPARE(right->session()->cursor()->point(), coronalBefore);
        QVERIFY(workspace->links()->lastNotice().contains(QStringLiteral("not scroll")));
        // ...and the coronal viewport shows the axial one's plane as a reference line.
        QCOMPARE(right->sliceView()->referencePlanes().size(), std::size_t{1});
        QCOMPARE(left->sliceView()->referencePlanes().size(), std::size_t{1});
    }

private:
    // The prior, listed by the study browser, dragged onto `right`.
    static void dropPriorOn(MainWindow& window, Viewport* right, const QString& priorDir,
                            const test::PriorStudy& prior) {
        auto* browser = window.findChild<StudyBrowser*>();
        QVERIFY(browser != nullptr);
        browser->addFolder(priorDir);
        QTRY_VERIFY_WITH_TIMEOUT(browser->pending() == 0, 30000);
        QTreeWidgetItem* item =
            browser->findSeries(priorDir, QString::fromStdString(prior.seriesUid));
        QVERIFY(item != nullptr);
        const QModelIndex index = browser->tree()->indexFromItem(item);
        std::unique_ptr<QMimeData> mime(browser->tree()->model()->mimeData({index}));
        QVERIFY(mime != nullptr);
        QSignalSpy shown(window.workspace(), &ViewportWorkspace::seriesShown);
        drop(right, mime.get());
        QVERIFY(shown.wait(60000));
    }

    // `steps` scrolls of the left viewport, `even` and `odd` notches in turn: the
    // right one's cursor lands within `tolerance` mm of the same anatomy each time.
    static void verifyLinkedScrolls(const Viewport& left, const Viewport& right, int steps,
                                    int even, int odd, double tolerance, const QString& what) {
        for (int step = 0; step < steps; ++step) {
            scroll(left.sliceView(), step % 2 == 0 ? even : odd);
            const double truth = left.session()->cursor()->point().z + kShift.z;
            const double landed = right.session()->cursor()->point().z;
            QVERIFY2(
                std::abs(landed - truth) <= tolerance,
                qPrintable(
                    QString("%1, step %2: %3 vs %4").arg(what).arg(step).arg(landed).arg(truth)));
        }
    }

    // Pixels: the linked viewport shows the prior's slice at its cursor, the one a
    // viewport of its own placed there shows, and not the slice it showed `before`.
    static void verifyPriorSliceShown(const Viewport& right, const QImage& before) {
        SliceView* b = right.sliceView();
        const QImage after = b->image();
        QVERIFY(differingPixels(before, after) > after.width() * after.height() / 100);
        MprCursor cursor;
        cursor.setWindow(right.session()->cursor()->windowCenter(),
                         right.session()->cursor()->windowWidth());
        cursor.setPoint(right.session()->cursor()->point());
        SliceView reference(Orientation::Axial, &cursor);
        reference.resize(b->size());
        reference.setVolume(right.session()->volume());
        reference.setZoomAndPan(b->zoom(), b->pan());
        QCOMPARE(differingPixels(reference.image(), after), 0);
    }

    // "Register" on the left viewport: the transform kept in the store takes
    // `anatomy` within 0.5 mm of where the prior shows it, and the pair's link is
    // the registration's.
    static void registerThePair(ViewportWorkspace& workspace, Viewport& left, const Viewport& right,
                                const QString& storeDir, const glm::dvec3& anatomy) {
        QSignalSpy registered(workspace.registration(), &ViewportRegistration::finished);
        QCOMPARE(workspace.registration()->registerWith(&left), 1);
        QVERIFY(registered.wait(180000));
        QVERIFY2(registered.first().at(0).toBool(),
                 qPrintable(registered.first().at(1).toString()));
        StudyStore store(storeDir.toStdString());
        const auto m = store.seriesTransform(left.session()->volume()->seriesUid,
                                             right.session()->volume()->seriesUid);
        QVERIFY(m.has_value());
        const glm::dvec3 landed = glm::dvec3(*m * glm::dvec4(anatomy, 1.0));
        QVERIFY2(glm::length(landed - (anatomy + kShift)) < 0.5,
                 qPrintable(QString("registered %1 mm from the truth")
                                .arg(glm::length(landed - (anatomy + kShift)))));
        QVERIFY(workspace.links()->linkBetween(*left.session(), *right.session()).kind ==
                SeriesLink::Kind::Registered);
    }

    QTemporaryDir settings_;
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestViewportGrid test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_viewport_grid.moc"
