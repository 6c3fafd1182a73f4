// Segments in the 3D view on the real head CT (512 x 512 x 140), CPU backend, offscreen: a
// rectangle drawn with the mouse over the lower part of the rendering (the skull base) cuts
// exactly the voxels whose centre projects into it (each projected here on its own), as one
// undo step; a freehand outline filled in, Escape dropping a drawing; the rendering masked by
// the segment; the segment's surface in its colour.
#include <QApplication>
#include <QPointer>
#include <QSignalSpy>
#include <QTest>

#include <memory>

#include "core/io/Catalog.h"
#include "core/scene/ViewFrame.h"
#include "core/segmentation/SegmentEffects.h"
#include "core/segmentation/Segmentation.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/RealData.h"
#include "ui/segmentation/MaskedRendering.h"
#include "ui/segmentation/Scissors3d.h"
#include "ui/segmentation/SegmentSurfaces3d.h"
#include "ui/volume/VolumeView.h"

using namespace lucent;

namespace {

constexpr const char* kHeadCt = "dcm_qa_ct/Philips_S21570/S2020";

// The voxels whose centre a w x h view with `camera` shows at a pixel position `inside` says.
template <class Inside>
SegmentMask projectingInto(const VolumeGeometry& g, const Camera& camera, int w, int h,
                           Inside inside) {
    const ViewFrame f = makeViewFrame(g, camera, w, h);
    SegmentMask out(g.dims);
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                const glm::dvec3 rel = g.toPatient(glm::dvec3(i, j, k)) - f.eye;
                const double z = glm::dot(rel, f.forward);
                if (z <= 1e-9) {
                    continue;
                }
                const double x =
                    (glm::dot(rel, f.right) / (z * f.tanHalfFov * f.aspect) + 1.0) * 0.5 * w;
                const double y = (1.0 - glm::dot(rel, f.up) / (z * f.tanHalfFov)) * 0.5 * h;
                if (inside(QPointF(x, y))) {
                    out.set(out.linearIndex(i, j, k));
                }
            }
        }
    }
    return out;
}

} // namespace

class TestScissors3d : public QObject {
    Q_OBJECT

    std::shared_ptr<const Volume> ct_;
    std::unique_ptr<VolumeView> view_;

private slots:
    void initTestCase() {
        REQUIRE_DATA(kHeadCt);
        ct_ = std::make_shared<const Volume>(loadPath(test::kRealData / kHeadCt));
        view_ = std::make_unique<VolumeView>(nullptr, VolumeView::Backend::Cpu);
        view_->resize(200, 160);
        view_->show();
        QVERIFY(QTest::qWaitForWindowExposed(view_.get()));
        view_->setVolume(ct_);
    }
    void cleanupTestCase() { view_.reset(); }

    void rectangleCutsTheLowerPartAndUndoes() {
        Segmentation segments(ct_->geometry());
        const std::uint32_t body = segments.add("Body");
        // The segment: everything above air (head, inserts and holder).
        const SegmentMask all = thresholdMask(*ct_, -500.0, 4000.0);
        QVERIFY(segments.setMask(body, all, "Threshold"));
        Scissors3d scissors(view_.get(), &segments, body);
        scissors.setShape(Scissors3d::Shape::Rectangle);
        scissors.setOperation(ScissorsOperation::EraseInside);
        scissors.setEnabled(true);
        QSignalSpy cuts(&scissors, &Scissors3d::cut);

        const Camera camera = view_->camera();
        const QPoint from(5, 96), to(195, 158);
        QTest::mousePress(view_.get(), Qt::LeftButton, {}, from);
        QTest::mouseMove(view_.get(), QPoint(100, 140));
        QVERIFY(scissors.drawing());
        QTest::mouseMove(view_.get(), to);
        QTest::mouseRelease(view_.get(), Qt::LeftButton, {}, to);
        QVERIFY(!scissors.drawing());
        // The drag drew: the camera did not turn.
        QCOMPARE(view_->camera().azimuth, camera.azimuth);
        QCOMPARE(view_->camera().elevation, camera.elevation);

        QCOMPARE(cuts.size(), 1);
        const SegmentMask inRectangle =
            projectingInto(ct_->geometry(), camera, 200, 160, [&](QPointF p) {
                return p.x() >= from.x() && p.x() <= to.x() && p.y() >= from.y() && p.y() <= to.y();
            });
        SegmentMask expected = all;
        expected.subtract(inRectangle);
        const std::size_t removed = all.count() - expected.count();
        qInfo("removed %zu of %zu voxels", removed, all.count());
        QVERIFY(removed > 1000);
        QCOMPARE(cuts.first().first().value<std::size_t>(), removed);
        QVERIFY(*segments.find(body)->mask == expected);
        QCOMPARE(QString::fromStdString(segments.undoText()), QString("Scissors"));
        QVERIFY(segments.undo());
        QVERIFY(*segments.find(body)->mask == all);
        QVERIFY(segments.redo());
        QVERIFY(*segments.find(body)->mask == expected);

        // Disabled: a left-drag turns the camera again and cuts nothing.
        scissors.setEnabled(false);
        QTest::mousePress(view_.get(), Qt::LeftButton, {}, QPoint(100, 80));
        QTest::mouseMove(view_.get(), QPoint(140, 80));
        QTest::mouseRelease(view_.get(), Qt::LeftButton, {}, QPoint(140, 80));
        QCOMPARE(cuts.size(), 1);
        QVERIFY(view_->camera().azimuth != camera.azimuth);
        view_->setCamera(camera);
    }

    // A freehand outline filled into an empty segment: the voxels whose centre projects
    // inside the polygon the mouse drew (even-odd, as written here); Escape drops a drawing.
    void freehandFillsInside() {
        Segmentation segments(ct_->geometry());
        const std::uint32_t cut = segments.add("Cut");
        Scissors3d scissors(view_.get(), &segments, cut);
        scissors.setShape(Scissors3d::Shape::Freehand);
        scissors.setOperation(ScissorsOperation::FillInside);
        scissors.setEnabled(true);
        const std::vector<QPoint> outline{{60, 40}, {150, 50}, {130, 120}, {100, 70}, {70, 110}};
        QTest::mousePress(view_.get(), Qt::LeftButton, {}, outline[0]);
        for (std::size_t n = 1; n < outline.size(); ++n) {
            QTest::mouseMove(view_.get(), outline[n]);
        }
        QTest::mouseRelease(view_.get(), Qt::LeftButton, {}, outline.back());
        const SegmentMask expected =
            projectingInto(ct_->geometry(), view_->camera(), 200, 160, [&](QPointF p) {
                bool in = false;
                for (std::size_t i = 0, j = outline.size() - 1; i < outline.size(); j = i++) {
                    const QPointF a = outline[i], b = outline[j];
                    if ((a.y() > p.y()) != (b.y() > p.y()) &&
                        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
                        in = !in;
                    }
                }
                return in;
            });
        QVERIFY(expected.count() > 100000);
        QVERIFY(segments.find(cut)->mask != nullptr);
        QVERIFY(*segments.find(cut)->mask == expected);

        QTest::mousePress(view_.get(), Qt::LeftButton, {}, QPoint(10, 10));
        QTest::mouseMove(view_.get(), QPoint(190, 10));
        QTest::mouseMove(view_.get(), QPoint(190, 150));
        QTest::keyClick(view_.get(), Qt::Key_Escape);
        QVERIFY(!scissors.drawing());
        QTest::mouseRelease(view_.get(), Qt::LeftButton, {}, QPoint(190, 150));
        QVERIFY(*segments.find(cut)->mask == expected); // nothing more cut
    }

    // Owned by the view: the view may go first, taking the scissors and their overlay along.
    void goesWithItsView() {
        Segmentation segments(ct_->geometry());
        auto view = std::make_unique<VolumeView>(nullptr, VolumeView::Backend::Cpu);
        QPointer<Scissors3d> scissors = new Scissors3d(view.get(), &segments, segments.add("A"));
        scissors->setEnabled(true);
        QTest::mousePress(view.get(), Qt::LeftButton, {}, QPoint(5, 5));
        QVERIFY(scissors->drawing());
        view.reset();
        QVERIFY(scissors.isNull());
    }

    void maskedRenderingAndSurface() {
        Segmentation segments(ct_->geometry());
        const std::uint32_t bone = segments.add("Bone", findSegmentKind("bone"));
        const SegmentMask boneMask = thresholdMask(*ct_, 300.0, 4000.0);
        QVERIFY(segments.setMask(bone, boneMask, "Threshold"));

        MaskedRendering masked(view_.get());
        Camera turned;
        turned.azimuth = 40.0;
        view_->setCamera(turned);
        masked.show(boneMask, MaskKeep::Outside);
        QVERIFY(masked.active());
        QVERIFY(view_->volume() != ct_);
        QCOMPARE(view_->camera().azimuth, 40.0); // kept across the switch
        const auto [lowest, highest] = ct_->valueRange();
        std::size_t checked = 0;
        boneMask.forEachSet([&](std::size_t i) {
            if (checked++ < 1000) {
                QCOMPARE(double(view_->volume()->voxels<std::int16_t>()[i]), lowest);
            }
        });
        masked.clear();
        QVERIFY(view_->volume() == ct_);

        SegmentSurfaces3d surfaces(view_.get(), &segments);
        const SurfaceResult& surface = surfaces.show(bone);
        QVERIFY(surface.mesh.triangles.size() > 1000);
        QVERIFY(view_->surfaceDisplay() != nullptr);
        const Segment* segment = segments.find(bone);
        QCOMPARE(view_->surfaceDisplay()->colour,
                 glm::dvec3(segment->colour[0], segment->colour[1], segment->colour[2]) / 255.0);
        QCOMPARE(view_->surfaceDisplay()->mesh->triangles.size(), surface.mesh.triangles.size());
        surfaces.hide();
        QVERIFY(view_->surfaceDisplay() == nullptr);
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestScissors3d test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_scissors3d.moc"
