// The Segments dock's tools wired as the main window wires them, on the real CT (28 slices)
// kept in a real study store: grow from seeds through the panel equals SeedGrower run on the
// same seeds, one undo step, and a later stroke grows again by itself from the previous
// result; the segments are saved as a SEG and read back onto a new session with nothing to
// undo; in a 3D viewport of the grid the rendering is masked by the segment and back, the
// segment's surface is shown and exported, and the scissors cut it with the mouse.
#include <QApplication>
#include <QCheckBox>
#include <QComboBox>
#include <QPushButton>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

#include <filesystem>
#include <memory>

#include "core/io/Catalog.h"
#include "core/scene/SurfaceDisplay.h"
#include "core/segdicom/SegmentationArchive.h"
#include "core/segmentation/GrowFromSeeds.h"
#include "core/segmentation/SegmentEffects.h"
#include "core/store/StudyStore.h"
#include "tests/core/report/StoredCopies.h"
#include "tests/core/segdicom/SegFileChecks.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/RealData.h"
#include "ui/segmentation/GrowFromSeedsEffect.h"
#include "ui/segmentation/Scissors3d.h"
#include "ui/segmentation/SegmentEditor.h"
#include "ui/segmentation/SegmentTools3d.h"
#include "ui/segmentation/SegmentationAutosave.h"
#include "ui/segmentation/SegmentationSession.h"
#include "ui/segmentation/SegmentationStoreSync.h"
#include "ui/segmentation/SegmentsPanel.h"
#include "ui/viewports/GridShape.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportWorkspace.h"
#include "ui/volume/VolumeView.h"

using namespace lucent;
namespace fs = std::filesystem;

namespace {

constexpr const char* kCt = "dcm_qa_ct/Philips_S21570/S2010";

// The voxels of slice k inside the box [lo, hi) of (i, j) whose value lies in [a, b].
SegmentMask seedsIn(const Volume& ct, int k, glm::ivec2 lo, glm::ivec2 hi, double a, double b) {
    const SegmentMask range = thresholdMask(ct, a, b);
    SegmentMask out(ct.dims());
    for (int j = lo.y; j < hi.y; ++j) {
        for (int i = lo.x; i < hi.x; ++i) {
            if (range.at(i, j, k)) {
                out.set(out.linearIndex(i, j, k));
            }
        }
    }
    return out;
}

} // namespace

class TestSegmentTools3d : public QObject {
    Q_OBJECT

    QTemporaryDir store_;
    std::shared_ptr<Volume> ct_;
    std::unique_ptr<SegmentationAutosave> autosave_;
    std::unique_ptr<ViewportWorkspace> workspace_;
    std::unique_ptr<SegmentEditor> editor_;
    std::unique_ptr<SegmentsPanel> panel_;
    std::unique_ptr<SegmentationStoreSync> sync_;
    std::unique_ptr<SegmentTools3d> tools_;
    std::uint32_t bone_ = 0, inside_ = 0;
    std::vector<SegmentMask> seeds_;

    SegmentationSession* session() const { return panel_->session(); }
    const SegmentMask& maskOf(std::uint32_t id) const {
        return *session()->segmentation().find(id)->mask;
    }
    VolumeView* viewOf(const Volume& series) const {
        for (Viewport* v : workspace_->grid()->viewports()) {
            if (v->volumeView() != nullptr && v->session() != nullptr &&
                v->session()->volume()->seriesUid == series.seriesUid) {
                return v->volumeView();
            }
        }
        return nullptr;
    }

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        {
            StudyStore store(store_.path().toStdString());
            for (const auto& e : fs::directory_iterator(test::kRealData / kCt)) {
                QVERIFY(test::storeCopy(store, e.path(), "CT"));
            }
        }
        ct_ = std::make_shared<Volume>(loadPath(test::kRealData / kCt));
        autosave_ = std::make_unique<SegmentationAutosave>(store_.path());
        workspace_ = std::make_unique<ViewportWorkspace>();
        workspace_->resize(900, 480);
        workspace_->grid()->setShape(*gridShape(QStringLiteral("1x2")));
        editor_ = std::make_unique<SegmentEditor>(workspace_.get());
        panel_ = std::make_unique<SegmentsPanel>(editor_.get());
        sync_ = std::make_unique<SegmentationStoreSync>(editor_->sessions(), autosave_.get());
        tools_ = std::make_unique<SegmentTools3d>(
            panel_.get(), [this](const Volume& series) { return viewOf(series); });
        panel_->addEffectWidget(tools_.get());
        Viewport* right = workspace_->grid()->viewports()[1];
        workspace_->grid()->setActiveViewport(right);
        workspace_->showVolume(ct_, QStringLiteral("ct"), QString());
        workspace_->show();
        QVERIFY(QTest::qWaitForWindowExposed(workspace_.get()));
        QVERIFY(session() != nullptr);
    }

    void cleanupTestCase() {
        if (sync_) {
            sync_->detachAll();
        }
        tools_.reset();
        sync_.reset();
        panel_.reset();
        editor_.reset();
        workspace_.reset();
        autosave_.reset();
    }

    void growsFromSeedsThroughThePanel() {
        REQUIRE_DATA(kCt);
        // Seeds on the middle slice: the skull's bone, and soft tissue inside it.
        const int k = ct_->dims().z / 2;
        seeds_ = {seedsIn(*ct_, k, {0, 0}, {512, 512}, 700.0, 4000.0),
                  seedsIn(*ct_, k, {236, 236}, {276, 276}, -50.0, 100.0)};
        QVERIFY(seeds_[0].count() > 500 && seeds_[1].count() > 200);
        bone_ = session()->addSegment(QStringLiteral("Bone"), findSegmentKind("bone"));
        inside_ = session()->addSegment(QStringLiteral("Inside"));
        QVERIFY(session()->apply(bone_, seeds_[0], QStringLiteral("Paint")));
        QVERIFY(session()->apply(inside_, seeds_[1], QStringLiteral("Paint")));
        session()->setActiveSegment(inside_);

        // The whole volume grown (margin 0): the same region for the first grow and the
        // update, so the update equals growing afresh voxel for voxel.
        tools_->grow()->setMarginMm(0.0);
        QVERIFY(tools_->growFromSeeds());
        SeedGrower direct(*ct_, GrowOptions{tools_->grow()->marginMm()});
        direct.grow(seeds_);
        QVERIFY(maskOf(bone_) == direct.masks()[0]);
        QVERIFY(maskOf(inside_) == direct.masks()[1]);
        QVERIFY(maskOf(inside_).count() > 50 * seeds_[1].count());
        const Segmentation& s = session()->segmentation();
        QCOMPARE(s.undoText(), std::string("Grow from seeds"));
        QCOMPARE(s.find(bone_)->algorithmName, std::string("Lucent grow from seeds"));
        QVERIFY(session()->undo()); // one step takes both back to their seeds
        QVERIFY(maskOf(bone_) == seeds_[0] && maskOf(inside_) == seeds_[1]);
        QVERIFY(session()->redo());

        // A stroke for "inside" with updates on: grown again from the previous result.
        tools_->growAfterStrokes()->setChecked(true);
        // The stroke: voxels of the middle slice grown into the bone though below its seeds'
        // 700 HU, painted for "inside" (a correction), within the grown box.
        const SegmentMask before = maskOf(inside_);
        SegmentMask stroke(ct_->dims());
        std::size_t strokeVoxels = 0;
        maskOf(bone_).forEachSet([&](std::size_t n) {
            if (stroke.voxelOf(n).z == k && !seeds_[0].get(n) && strokeVoxels < 200) {
                stroke.set(n);
                ++strokeVoxels;
            }
        });
        SegmentMask gained = stroke;
        gained.subtract(before);
        QVERIFY(gained.any());
        SegmentMask painted = before;
        painted |= stroke;
        QVERIFY(session()->apply(inside_, painted, QStringLiteral("Paint")));
        QCOMPARE(s.undoText(), std::string("Grow from seeds"));
        QVERIFY(tools_->grow()->lastOutcome().incremental);
        std::vector<SegmentMask> seeds = seeds_;
        seeds[0].subtract(gained);
        seeds[1] |= gained;
        SeedGrower afresh(*ct_, GrowOptions{tools_->grow()->marginMm()});
        afresh.grow(seeds);
        QVERIFY(maskOf(bone_) == afresh.masks()[0]);
        QVERIFY(maskOf(inside_) == afresh.masks()[1]);
        tools_->growAfterStrokes()->setChecked(false);

        // Fewer than two seeded segments: refused, saying why.
        session()->setVisible(bone_, false);
        QSignalSpy said(tools_.get(), &SegmentTools3d::message);
        QVERIFY(!tools_->growFromSeeds());
        QVERIFY(said.last().at(0).toString().contains(QStringLiteral("two or more")));
        session()->setVisible(bone_, true);
    }

    void savedAsSegAndOpenedAgain() {
        REQUIRE_DATA(kCt);
        autosave_->flush(); // what the debounce has not saved yet
        // A new window's sessions: the stored SEG comes back, with nothing to undo.
        SegmentationAutosave again(store_.path());
        SegmentationSessions sessions;
        SegmentationStoreSync sync(&sessions, &again);
        SegmentationSession* reopened = sessions.sessionFor(ct_);
        QVERIFY(reopened != nullptr);
        const Segmentation& read = reopened->segmentation();
        QCOMPARE(read.segments().size(), std::size_t(2));
        QCOMPARE(read.segments()[0].name, std::string("Bone"));
        QVERIFY(*read.segments()[0].mask == maskOf(bone_));
        QVERIFY(*read.segments()[1].mask == maskOf(inside_));
        QVERIFY(!read.canUndo());
        sync.detachAll();
    }

    // A SEG Lucent reads but would not write back as it was (FRACTIONAL) opens locked.
    void fractionalSegOpensLocked() {
        REQUIRE_DATA(kCt);
        autosave_->flush();
        const QTemporaryDir here;
        const fs::path fractional = fs::path(here.path().toStdString()) / "fractional.dcm";
        {
            StudyStore store(store_.path().toStdString());
            SegmentationArchive archive(store);
            const std::vector<SegmentationArchive::Stored> held = archive.find(ct_->seriesUid);
            QCOMPARE(held.size(), std::size_t(1));
            test::toFractional(held.front().file, fractional);
            store.remove(held.front().header.sopInstanceUid);
            QVERIFY(test::storeCopy(store, fractional, "SEG"));
        }
        SegmentationAutosave again(store_.path());
        SegmentationSessions sessions;
        SegmentationStoreSync sync(&sessions, &again);
        QSignalSpy said(&sync, &SegmentationStoreSync::message);
        SegmentationSession* reopened = sessions.sessionFor(ct_);
        QVERIFY(reopened != nullptr);
        const Segmentation& read = reopened->segmentation();
        QCOMPARE(read.segments().size(), std::size_t(2));
        QVERIFY(read.segments()[0].locked && read.segments()[1].locked);
        QVERIFY(*read.segments()[1].mask == maskOf(inside_));
        QVERIFY(said.last().at(0).toString().contains(QStringLiteral("2 locked")));
        sync.detachAll();
    }

    void showsAndCutsInThe3dView() {
        REQUIRE_DATA(kCt);
        QSignalSpy said(tools_.get(), &SegmentTools3d::message);
        QVERIFY(!tools_->showMasked(true)); // no 3D view of the series yet
        QVERIFY(said.last().at(0).toString().contains(QStringLiteral("no 3D view")));
        Viewport* left = workspace_->grid()->viewports()[0];
        left->show(workspace_->grid()->viewports()[1]->session(), ViewportView::Volume3D);
        VolumeView* view = left->volumeView();
        QVERIFY(view != nullptr);
        QTRY_VERIFY(view->volume() != nullptr);
        const std::shared_ptr<const Volume> original = view->volume();

        session()->setActiveSegment(inside_);
        QVERIFY(tools_->showMasked(true));
        const std::shared_ptr<const Volume> masked = view->volume();
        QVERIFY(masked != original);
        const SegmentMask& inside = maskOf(inside_);
        std::size_t checked = 0;
        for (std::size_t n = 0; n < inside.size(); n += 997) {
            const glm::ivec3 v = inside.voxelOf(n);
            const double want =
                inside.get(n) ? original->value(v.x, v.y, v.z) : ct_->valueRange().first;
            QCOMPARE(masked->value(v.x, v.y, v.z), want);
            checked += inside.get(n) ? 1 : 0;
        }
        QVERIFY(checked > 0);
        QVERIFY(tools_->showWholeVolume());
        QVERIFY(view->volume() == original);

        QVERIFY(tools_->showSurface());
        QVERIFY(view->surfaceDisplay() && view->surfaceDisplay()->mesh &&
                !view->surfaceDisplay()->mesh->empty());
        QTemporaryDir out;
        const QString stl = out.filePath(QStringLiteral("inside.stl"));
        QVERIFY(tools_->exportSurface(stl));
        QVERIFY(fs::file_size(stl.toStdString()) > 84);

        // Scissors: a rectangle over the whole view erases every voxel in front of the eye.
        QSignalSpy changed(session(), &SegmentationSession::segmentsChanged);
        tools_->scissorsShape()->setCurrentIndex(2);
        tools_->scissorsButton()->setChecked(true);
        QVERIFY(tools_->scissors() != nullptr && tools_->scissors()->enabled());
        const QPoint from(1, 1), to(view->width() - 2, view->height() - 2);
        QTest::mousePress(view, Qt::LeftButton, {}, from);
        QTest::mouseMove(view, QPoint(view->width() / 2, view->height() / 2));
        QTest::mouseMove(view, to);
        QTest::mouseRelease(view, Qt::LeftButton, {}, to);
        QVERIFY(!changed.isEmpty());
        QCOMPARE(session()->segmentation().undoText(), std::string("Scissors"));
        QVERIFY(maskOf(inside_).count() < inside.count());
        QVERIFY(session()->undo());
        tools_->scissorsButton()->setChecked(false);
        QVERIFY(tools_->scissors() == nullptr);

        // The 3D view going (the viewport turned to MPR) takes the scissors with it.
        tools_->scissorsButton()->setChecked(true);
        QVERIFY(tools_->scissors() != nullptr);
        left->show(workspace_->grid()->viewports()[1]->session(), ViewportView::Axial);
        QTRY_VERIFY(tools_->scissors() == nullptr);
        QVERIFY(!tools_->scissorsButton()->isChecked());
        QVERIFY(!tools_->showMasked(true)); // and no 3D view is left to mask
    }
};

int main(int argc, char** argv) {
    test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestSegmentTools3d test;
    return QTest::qExec(&test, argc, argv);
}
#include "test_segment_tools3d.moc"
