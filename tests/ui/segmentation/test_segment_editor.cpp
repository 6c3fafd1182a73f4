// The Segment Editor in the viewport grid on the real 140-slice CT: a brush click and a
// stroke through synthesized mouse events against the spheres computed by hand, a locked
// segment left alone, the threshold (preview and apply) against thresholdMask, undo and
// redo (Ctrl+Z and Ctrl+Y in the panel), an outline dragged and filled on the slice, the
// fill drawn in the view, the statistics CSV against SegmentStatistics, and labelmap NIfTI
// export and import through the panel (bad files named in the message). Offscreen.
#include <QAction>
#include <QApplication>
#include <QFile>
#include <QPushButton>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTest>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/formats/NiftiWrite.h"
#include "core/io/Catalog.h"
#include "core/segmentation/SegmentEffects.h"
#include "core/segmentation/SegmentSmoothing.h"
#include "core/segmentation/SegmentStatistics.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/RealData.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SliceView.h"
#include "ui/segmentation/SegmentEditor.h"
#include "ui/segmentation/SegmentationSession.h"
#include "ui/segmentation/SegmentsPanel.h"
#include "ui/segmentation/SliceSegments.h"
#include "ui/viewports/GridShape.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportWorkspace.h"

using namespace lucent;

namespace {

constexpr const char* kCt = "dcm_qa_ct/Philips_S21570/S2020";

// The voxels whose centre lies within r mm of `centre`, by a loop over the index box.
SegmentMask sphereByHand(const VolumeGeometry& g, const glm::dvec3& centre, double r) {
    SegmentMask out(g.dims);
    const glm::dvec3 c = g.toIndex(centre);
    const glm::ivec3 reach(glm::ceil(glm::dvec3(r) / g.spacing) + 1.0);
    for (int k = int(c.z) - reach.z; k <= int(c.z) + reach.z; ++k) {
        for (int j = int(c.y) - reach.y; j <= int(c.y) + reach.y; ++j) {
            for (int i = int(c.x) - reach.x; i <= int(c.x) + reach.x; ++i) {
                if (out.inside({i, j, k}) &&
                    glm::length(g.toPatient(glm::dvec3(i, j, k)) - centre) <= r) {
                    out.set(out.linearIndex(i, j, k));
                }
            }
        }
    }
    return out;
}

std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out(1);
    for (const char c : line) {
        if (c == ',') {
            out.emplace_back();
        } else {
            out.back().push_back(c);
        }
    }
    return out;
}

} // namespace

class TestSegmentEditor : public QObject {
    Q_OBJECT

    std::shared_ptr<Volume> ct_;
    std::unique_ptr<ViewportWorkspace> workspace_;
    std::unique_ptr<SegmentEditor> editor_;
    std::unique_ptr<SegmentsPanel> panel_;
    SliceView* view_ = nullptr;
    SegmentMask afterPaint_;
    QTemporaryDir dir_;

    SegmentationSession* session() const { return editor_->sessions()->find(*ct_); }
    const SegmentMask& maskOf(std::uint32_t id) const {
        return *session()->segmentation().find(id)->mask;
    }

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        ct_ = std::make_shared<Volume>(loadPath(test::kRealData / kCt));
        QCOMPARE(ct_->dims().z, 140);
        workspace_ = std::make_unique<ViewportWorkspace>();
        workspace_->resize(900, 520);
        workspace_->grid()->setShape(*gridShape(QStringLiteral("1x2")));
        editor_ = std::make_unique<SegmentEditor>(workspace_.get());
        panel_ = std::make_unique<SegmentsPanel>(editor_.get());
        Viewport* right = workspace_->grid()->viewports()[1];
        workspace_->grid()->setActiveViewport(right);
        workspace_->showVolume(ct_, QStringLiteral("ct"), QString());
        workspace_->show();
        panel_->show();
        QVERIFY(QTest::qWaitForWindowExposed(workspace_.get()));
        view_ = right->sliceView();
        QVERIFY(view_ != nullptr && editor_->layerOf(view_) != nullptr);
        // The crosshair on a voxel centre: the slice is one voxel layer, exactly.
        right->session()->cursor()->setPoint(ct_->geometry().toPatient(glm::dvec3(256, 250, 70)));
        QVERIFY(panel_->session() != nullptr && panel_->session() == session());
    }

    void paintsTheBrushSphere() {
        REQUIRE_DATA(kCt);
        editor_->setTool(SegmentTool::Paint);
        editor_->setBrushRadiusMm(6.0);
        const QPoint at(view_->width() / 2 + 7, view_->height() / 2 - 5);
        const glm::dvec3 centre = view_->plane().pointAt(at.x(), at.y());
        const glm::dvec3 crosshair = view_->plane().centre;
        QTest::mouseClick(view_, Qt::LeftButton, Qt::NoModifier, at);
        QCOMPARE(view_->plane().centre, crosshair); // the tool took the button
        SegmentationSession* s = session();
        QCOMPARE(s->segmentation().segments().size(), std::size_t{1}); // made for the stroke
        const SegmentMask want = sphereByHand(ct_->geometry(), centre, 6.0);
        QVERIFY(want.count() > 1000);
        QCOMPARE(maskOf(s->activeSegment()).count(), want.count());
        QVERIFY(maskOf(s->activeSegment()) == want);
        QCOMPARE(s->segmentation().undoText(), std::string("Paint"));

        // A stroke: one undo step, covering the spheres at both ends.
        const std::uint64_t before = s->segmentation().revision();
        const QPoint from(view_->width() / 2 - 60, view_->height() / 2 + 40);
        const QPoint to(view_->width() / 2 - 20, view_->height() / 2 + 60);
        const glm::dvec3 a = view_->plane().pointAt(from.x(), from.y());
        const glm::dvec3 b = view_->plane().pointAt(to.x(), to.y());
        QTest::mousePress(view_, Qt::LeftButton, Qt::NoModifier, from);
        QVERIFY(s->preview().has_value()); // the stroke shows while it is painted
        QTest::mouseMove(view_, (from + to) / 2);
        QTest::mouseMove(view_, to);
        QTest::mouseRelease(view_, Qt::LeftButton, Qt::NoModifier, to);
        QVERIFY(!s->preview().has_value());
        QCOMPARE(s->segmentation().revision(), before + 1);
        SegmentMask ends = sphereByHand(ct_->geometry(), a, 6.0);
        ends |= sphereByHand(ct_->geometry(), b, 6.0);
        SegmentMask missing = ends;
        QVERIFY(!missing.subtract(maskOf(s->activeSegment())).any());
        for (int t = 0; t <= 10; ++t) { // the line between them: the moves painted too
            const glm::ivec3 v(glm::round(ct_->geometry().toIndex(a + (b - a) * (t / 10.0))));
            QVERIFY(maskOf(s->activeSegment()).at(v.x, v.y, v.z));
        }
        afterPaint_ = maskOf(s->activeSegment());
        QVERIFY(s->undo());
        QVERIFY(maskOf(s->activeSegment()) == want);
        QVERIFY(s->redo());
        QVERIFY(maskOf(s->activeSegment()) == afterPaint_);

        // The slice brush: the disc on this slice alone (the erase of a sphere here).
        editor_->setTool(SegmentTool::Erase);
        editor_->setBrushSphere(false);
        QTest::mouseClick(view_, Qt::LeftButton, Qt::NoModifier, at);
        SegmentMask disc(ct_->dims());
        const int slice = static_cast<int>(std::lround(ct_->geometry().toIndex(centre).z));
        want.forEachSet([&](std::size_t i) {
            if (want.voxelOf(i).z == slice) {
                disc.set(i);
            }
        });
        SegmentMask expected = afterPaint_;
        QVERIFY(maskOf(s->activeSegment()) == expected.subtract(disc));
        QVERIFY(s->undo());
        editor_->setBrushSphere(true);
    }

    void lockedSegmentIsLeftAlone() {
        REQUIRE_DATA(kCt);
        SegmentationSession* s = session();
        const std::uint32_t id = s->activeSegment();
        s->setLocked(id, true);
        editor_->setTool(SegmentTool::Paint);
        const std::uint64_t revision = s->segmentation().revision();
        QTest::mouseClick(view_, Qt::LeftButton, Qt::NoModifier, {40, 60});
        QCOMPARE(s->segmentation().revision(), revision);
        QVERIFY(editor_->lastMessage().contains(QStringLiteral("locked")));
        QVERIFY(!panel_->margin(2.0));
        // A tool added by another room gets the session and the segment, unless locked.
        std::uint32_t handed = 0;
        QPushButton* more =
            panel_->addEffectButton(QStringLiteral("Scissors"), QString(),
                                    [&](SegmentationSession& session, std::uint32_t segment) {
                                        QCOMPARE(&session, s);
                                        handed = segment;
                                    });
        more->click();
        QCOMPARE(handed, std::uint32_t{0});
        QVERIFY(panel_->lastMessage().contains(QStringLiteral("locked")));
        s->setLocked(id, false);
        more->click();
        QCOMPARE(handed, id);
        editor_->setTool(SegmentTool::None);
    }

    void thresholdsAndUndoes() {
        REQUIRE_DATA(kCt);
        SegmentationSession* s = session();
        const std::uint32_t id = s->activeSegment();
        const SegmentMask want = thresholdMask(*ct_, 250.0, 2000.0);
        panel_->setThresholdRange(250.0, 2000.0);
        panel_->setThresholdPreview(true);
        QVERIFY(s->preview().has_value() && *s->preview()->mask == want);
        QVERIFY(maskOf(id) == afterPaint_); // a preview changes nothing
        QVERIFY(panel_->applyThreshold());
        QVERIFY(!s->preview().has_value());
        QVERIFY(maskOf(id) == want);
        QCOMPARE(s->segmentation().find(id)->algorithmName, std::string("Lucent threshold"));

        // The fill in the view: a pixel on bone inside the mask, one on air outside.
        SliceSegments* layer = editor_->layerOf(view_);
        layer->grab();
        const QImage& overlay = layer->lastOverlay();
        QVERIFY(!overlay.isNull());
        const SlicePlane plane = view_->plane();
        int inside = 0, outside = 0;
        for (int y = 1; y + 1 < plane.height; y += 3) {
            for (int x = 1; x + 1 < plane.width; x += 3) {
                const glm::ivec3 v(glm::floor(ct_->geometry().toIndex(plane.pointAt(x, y)) + 0.5));
                if (!want.inside(v)) {
                    continue;
                }
                const int alpha = qAlpha(overlay.pixel(x, y));
                if (want.at(v.x, v.y, v.z)) {
                    QVERIFY(alpha > 0);
                    ++inside;
                } else {
                    QCOMPARE(alpha, 0);
                    ++outside;
                }
            }
        }
        QVERIFY(inside > 20 && outside > 1000);

        // Ctrl+Z and Ctrl+Y within the panel, though its window has an Undo of its own (the
        // main window's Edit > Undo).
        QAction windowUndo;
        windowUndo.setShortcuts({QKeySequence::Undo, QKeySequence(QStringLiteral("Ctrl+Y"))});
        int windowUndos = 0;
        connect(&windowUndo, &QAction::triggered, this, [&] { ++windowUndos; });
        panel_->addAction(&windowUndo);
        panel_->activateWindow();
        panel_->segmentTable()->setFocus();
        QVERIFY(QTest::qWaitForWindowActive(panel_.get()));
        QTest::keyClick(panel_->segmentTable(), Qt::Key_Z, Qt::ControlModifier);
        QVERIFY(maskOf(id) == afterPaint_);
        QTest::keyClick(panel_->segmentTable(), Qt::Key_Y, Qt::ControlModifier);
        QVERIFY(maskOf(id) == want);
        QCOMPARE(windowUndos, 0);
        panel_->removeAction(&windowUndo);
    }

    void effectsOnTheActiveSegment() {
        REQUIRE_DATA(kCt);
        SegmentationSession* s = session();
        const std::uint32_t id = s->activeSegment();
        const VolumeGeometry& g = ct_->geometry();
        const SegmentMask bone = maskOf(id);
        QVERIFY(panel_->removeSmallIslands(50.0));
        QVERIFY(maskOf(id) == removeSmallIslands(bone, g, 50.0));
        QVERIFY(panel_->keepLargestIsland());
        QVERIFY(maskOf(id) == keepLargestIsland(removeSmallIslands(bone, g, 50.0)));
        QVERIFY(panel_->invert());
        SegmentMask inverted = keepLargestIsland(removeSmallIslands(bone, g, 50.0));
        QVERIFY(maskOf(id) == inverted.invert());
        for (int n = 0; n < 3; ++n) {
            QVERIFY(s->undo());
        }
        QVERIFY(maskOf(id) == bone);
    }

    void drawsAnOutline() {
        REQUIRE_DATA(kCt);
        SegmentationSession* s = session();
        panel_->addSegment();
        const std::uint32_t id = s->activeSegment();
        QCOMPARE(s->segmentation().segments().size(), std::size_t{2});
        editor_->setTool(SegmentTool::Draw);
        const int cx = view_->width() / 2, cy = view_->height() / 2;
        const QPoint corners[] = {
            {cx - 50, cy - 30}, {cx + 40, cy - 30}, {cx + 40, cy + 35}, {cx - 50, cy + 35}};
        QTest::mousePress(view_, Qt::LeftButton, Qt::NoModifier, corners[0]);
        for (int side = 0; side < 4; ++side) {
            const QPoint p = corners[side], q = corners[(side + 1) % 4];
            for (int t = 1; t <= 10; ++t) {
                QTest::mouseMove(view_, p + (q - p) * t / 10);
            }
        }
        QTest::mouseRelease(view_, Qt::LeftButton, Qt::NoModifier, corners[0]);
        // By hand: this slice's voxels whose centre lies inside the rectangle.
        const SlicePlane plane = view_->plane();
        const VolumeGeometry& g = ct_->geometry();
        const int slice = static_cast<int>(std::lround(g.toIndex(plane.centre).z));
        SegmentMask want(g.dims);
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                const glm::dvec2 p = plane.pixelOf(g.toPatient(glm::dvec3(i, j, slice)));
                for (const double edge :
                     {p.x - (cx - 50), p.x - (cx + 40), p.y - (cy - 30), p.y - (cy + 35)}) {
                    QVERIFY(std::abs(edge) > 1e-6); // no centre on an edge: exact
                }
                if (p.x > cx - 50 && p.x < cx + 40 && p.y > cy - 30 && p.y < cy + 35) {
                    want.set(want.linearIndex(i, j, slice));
                }
            }
        }
        QVERIFY(want.count() > 1000);
        QCOMPARE(maskOf(id).count(), want.count());
        QVERIFY(maskOf(id) == want);

        // Corners clicked, a double-click ends it: the triangle's voxels on this slice.
        QVERIFY(s->undo());
        const QPoint a(cx - 40, cy - 40), b(cx + 50, cy - 10), c(cx - 10, cy + 45);
        for (const QPoint& p : {a, b, c}) {
            QTest::mouseClick(view_, Qt::LeftButton, Qt::NoModifier, p);
        }
        QCOMPARE(editor_->layerOf(view_)->outline().size(), std::size_t{3});
        QVERIFY(!maskOf(id).any());
        QTest::mouseDClick(view_, Qt::LeftButton, Qt::NoModifier, c);
        QVERIFY(editor_->layerOf(view_)->outline().empty());
        const auto side = [](QPoint p, QPoint q, glm::dvec2 r) {
            return (q.x() - p.x()) * (r.y - p.y()) - (q.y() - p.y()) * (r.x - p.x());
        };
        SegmentMask triangle(g.dims);
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                const glm::dvec2 p = plane.pixelOf(g.toPatient(glm::dvec3(i, j, slice)));
                const double s1 = side(a, b, p), s2 = side(b, c, p), s3 = side(c, a, p);
                QVERIFY(std::abs(s1) > 1e-6 && std::abs(s2) > 1e-6 && std::abs(s3) > 1e-6);
                if ((s1 > 0 && s2 > 0 && s3 > 0) || (s1 < 0 && s2 < 0 && s3 < 0)) {
                    triangle.set(triangle.linearIndex(i, j, slice));
                }
            }
        }
        QVERIFY(triangle.count() > 1000);
        QVERIFY(maskOf(id) == triangle);
        editor_->setTool(SegmentTool::None);
    }

    void panelEffectsAreTheCoreOnes() {
        REQUIRE_DATA(kCt);
        SegmentationSession* s = session();
        const VolumeGeometry& g = ct_->geometry();
        // After drawsAnOutline: the bone, then the triangle (active).
        QCOMPARE(s->segmentation().segments().size(), std::size_t{2});
        const std::uint32_t triangle = s->activeSegment();
        const std::uint32_t id = s->segmentation().segments().front().id; // the bone
        s->setActiveSegment(id);
        const SegmentMask bone = maskOf(id);
        // Another segment over part of the bone: 100 to 400 HU.
        const std::uint32_t band = s->addSegment(QStringLiteral("Band"));
        QVERIFY(s->apply(band, thresholdMask(*ct_, 100.0, 400.0), QStringLiteral("Band")));
        s->setActiveSegment(id);
        const std::uint64_t steps = s->segmentation().revision();
        const auto check = [&](bool applied, const SegmentMask& want) {
            QVERIFY(applied);
            QVERIFY(maskOf(id) == want);
            QVERIFY(s->undo());
            QVERIFY(maskOf(id) == bone);
        };
        check(panel_->margin(2.0), marginMask(bone, g, 2.0));
        check(panel_->margin(-1.0), marginMask(bone, g, -1.0));
        check(panel_->hollow(1.0), hollowMask(bone, g, 1.0));
        check(panel_->median(3.0), medianMask(bone, g, 3.0));
        check(panel_->closing(2.0), closingMask(bone, g, 2.0));
        SegmentMask sum = bone, difference = bone, common = bone;
        sum |= maskOf(band);
        difference.subtract(maskOf(band));
        common &= maskOf(band);
        check(panel_->combine(SegmentsPanel::Logical::Add, band), sum);
        check(panel_->combine(SegmentsPanel::Logical::Subtract, band), difference);
        check(panel_->combine(SegmentsPanel::Logical::Intersect, band), common);
        QVERIFY(!panel_->combine(SegmentsPanel::Logical::Add, id)); // not with itself
        QCOMPARE(s->segmentation().revision(), steps + 16);         // 8 effects, 8 undos
        QVERIFY(s->removeSegment(band));
        s->setActiveSegment(triangle);

        // A name typed into the list: one step, undone by Ctrl+Z in the panel.
        QTableWidget* table = panel_->segmentTable();
        QTableWidgetItem* name = table->item(1, 2);
        QVERIFY(name != nullptr);
        name->setText(QStringLiteral("Tumour"));
        QTRY_COMPARE(s->segmentation().find(triangle)->name, std::string("Tumour"));
        QCOMPARE(table->item(1, 2)->text(), QStringLiteral("Tumour"));
        QVERIFY(panel_->undo());
        QCOMPARE(s->segmentation().find(triangle)->name, std::string("Segment 2"));
        QCOMPARE(table->item(1, 2)->text(), QStringLiteral("Segment 2"));
        // A row chosen in the list is the segment the effects act on.
        table->selectRow(0);
        QCOMPARE(s->activeSegment(), id);
        table->selectRow(1);
        QCOMPARE(s->activeSegment(), triangle);
    }

    void obliqueViewShowsTheNearestVoxels() {
        REQUIRE_DATA(kCt);
        SegmentationSession* s = session();
        SegmentMask shown(ct_->dims()); // every segment is visible
        for (const Segment& segment : s->segmentation().segments()) {
            shown |= *segment.mask;
        }
        MprCursor* cursor = workspace_->grid()->viewports()[1]->session()->cursor();
        cursor->setRotation(Orientation::Axial,
                            glm::dmat3(glm::rotate(glm::dmat4(1.0), glm::radians(25.0),
                                                   glm::normalize(glm::dvec3(1.0, 0.4, 0.0)))));
        SliceSegments* layer = editor_->layerOf(view_);
        layer->grab();
        const QImage& overlay = layer->lastOverlay();
        const SlicePlane plane = view_->plane();
        QVERIFY(std::abs(plane.normal().z) < 0.95); // oblique
        QCOMPARE(overlay.size(), QSize(plane.width, plane.height));
        int inside = 0, outside = 0;
        for (int y = 0; y < plane.height; y += 2) {
            for (int x = 0; x < plane.width; x += 2) {
                // The nearest voxel, by rounding the continuous index.
                const glm::dvec3 ijk = ct_->geometry().toIndex(plane.pointAt(x, y));
                const glm::ivec3 v(std::lround(ijk.x), std::lround(ijk.y), std::lround(ijk.z));
                if (!shown.inside(v) ||
                    glm::any(glm::lessThan(glm::abs(glm::fract(ijk) - 0.5), glm::dvec3(1e-6)))) {
                    continue; // outside, or halfway between two voxels
                }
                const bool set = shown.at(v.x, v.y, v.z);
                QCOMPARE(qAlpha(overlay.pixel(x, y)) > 0, set);
                (set ? inside : outside) += 1;
            }
        }
        QVERIFY(inside > 100 && outside > 1000);
        cursor->resetRotations();
    }

    void statisticsCsv() {
        REQUIRE_DATA(kCt);
        const QString path = dir_.filePath(QStringLiteral("stats.csv"));
        QVERIFY2(panel_->exportStatisticsCsv(path), qPrintable(panel_->lastMessage()));
        QFile file(path);
        QVERIFY(file.open(QIODevice::ReadOnly));
        const QStringList lines =
            QString::fromUtf8(file.readAll()).split(QStringLiteral("\r\n"), Qt::SkipEmptyParts);
        const auto& segments = session()->segmentation().segments();
        QCOMPARE(lines.size(), static_cast<int>(segments.size()) + 1);
        QVERIFY(lines[0].startsWith(QStringLiteral("segment,voxels,volume_ml,mean,sd")));
        QCOMPARE(panel_->statisticsTable()->rowCount(), static_cast<int>(segments.size()));
        for (std::size_t n = 0; n < segments.size(); ++n) {
            const SegmentStatistics want = segmentStatistics(*segments[n].mask, *ct_);
            const std::vector<std::string> f = split(lines[int(n) + 1].toStdString());
            QCOMPARE(f.size(), std::size_t{10});
            QCOMPARE(f[0], segments[n].name);
            QCOMPARE(std::stoull(f[1]), want.voxels);
            const double values[] = {
                want.volumeMl, want.mean,   want.standardDeviation, want.minimum,
                want.maximum,  want.median, want.surfaceAreaCm2,    want.largestDiameterMm};
            for (int c = 0; c < 8; ++c) {
                const std::string& field = f[std::size_t(c) + 2];
                if (field.empty()) { // what an empty segment has not
                    QVERIFY(std::isnan(values[c]));
                } else {
                    QCOMPARE(std::stod(field), values[c]); // 17 digits: exact
                }
            }
        }
    }

    void labelmapRoundTrip() {
        REQUIRE_DATA(kCt);
        SegmentationSession* s = session();
        const std::vector<Segment> before = s->segmentation().segments();
        const QString path = dir_.filePath(QStringLiteral("labels.nii.gz"));
        QVERIFY2(panel_->exportLabelmap(path), qPrintable(panel_->lastMessage()));
        QVERIFY2(panel_->importLabelmap(path), qPrintable(panel_->lastMessage()));
        const auto& after = s->segmentation().segments();
        QCOMPARE(after.size(), before.size() * 2);
        // Label n is segment n where no later segment lies over it.
        for (std::size_t n = 0; n < before.size(); ++n) {
            SegmentMask want = *before[n].mask;
            for (std::size_t later = n + 1; later < before.size(); ++later) {
                want.subtract(*before[later].mask);
            }
            QVERIFY(*after[before.size() + n].mask == want);
        }
        // Bad files: the message names them.
        const QString missing = dir_.filePath(QStringLiteral("none.nii"));
        QVERIFY(!panel_->importLabelmap(missing));
        QVERIFY2(panel_->lastMessage().contains(missing), qPrintable(panel_->lastMessage()));
        const QString small = dir_.filePath(QStringLiteral("small.nii"));
        VolumeGeometry g;
        g.dims = {4, 4, 4};
        writeNifti(small.toStdString(), Volume(g, VoxelType::UInt16));
        QVERIFY(!panel_->importLabelmap(small));
        QVERIFY2(panel_->lastMessage().contains(small), qPrintable(panel_->lastMessage()));
        QCOMPARE(s->segmentation().segments().size(), before.size() * 2);
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestSegmentEditor test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_segment_editor.moc"
