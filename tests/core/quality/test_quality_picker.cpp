// The quality picker of the 3D view's controls, on a real VolumeView: on the
// CPU, Fast measures the volume's front once in the background and sets the
// view's sampling to a point of it, and dragging to a coarser measured step
// of the same filter; Best picks a point at least as accurate at once from
// the same front; an unreachable target falls back to the fastest with a
// message; Manual gives the view its own sampling back; a second panel reads
// the front from the cache dir. On the GPU (llvmpipe under Xvfb) the front is
// measured with the GPU ray caster in an offscreen context of its own.
#include <QApplication>
#include <QComboBox>
#include <QDir>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QTest>

#include <cstdio>
#include <vector>

#include <unistd.h>

#include "core/quality/MeasuredFront.h"
#include "tests/core/raycast/RaycastScenes.h"
#include "tests/support/XvfbRelaunch.h"
#include "ui/volume/VolumeView.h"
#include "ui/volume/VolumeViewControls.h"

using namespace lucent;

namespace {

// The front point the view's sampling is, or nullptr.
const QualityPoint* pointOf(const MeasuredFront& front, const VolumeView& view) {
    const SamplingSettings& s = view.sampling();
    for (const QualityPoint& p : front.points) {
        if (p.setting.step == s.step && p.setting.interpolation == s.interpolation &&
            p.setting.classification == s.classification &&
            p.setting.preintegrate == s.preintegrate &&
            p.setting.shading == view.transferFunction().shading.enabled) {
            return &p;
        }
    }
    return nullptr;
}

} // namespace

class TestQualityPicker : public QObject {
    Q_OBJECT
    QTemporaryDir cache_;

private slots:
    void pickerChoosesFromTheMeasuredFront() {
        VolumeView view(nullptr, VolumeView::Backend::Cpu);
        view.resize(160, 128);
        view.setVolume(std::make_shared<Volume>(
            test::makeVolume({40, 36, 32}, test::blobs, VoxelType::Int16)));
        view.setTransferFunction(test::rampTf(true));
        SamplingSettings own = view.sampling();
        own.step = 0.75; // not a step of the quick sweep
        view.setSampling(own);
        VolumeViewControls controls(&view);
        controls.setQualityCacheDir(cache_.path());
        QSignalSpy chosen(&controls, &VolumeViewControls::qualityChosen);

        controls.qualityPicker()->setCurrentIndex(1); // Fast
        QVERIFY2(controls.qualityStatus().contains("Measuring"),
                 qPrintable(controls.qualityStatus()));
        QVERIFY(chosen.wait(240000));
        const auto front =
            loadFront(cache_.path().toStdString(), frontKey(view.description(), "cpu"));
        QVERIFY2(front, "the measured front is in the cache dir");
        const QualityPoint* fast = pointOf(*front, view);
        QVERIFY2(fast && fast->pareto, qPrintable(controls.qualityStatus()));
        // Dragging: a measured step of the same filter, no finer than the still one.
        const InteractiveQuality drag = controls.dragQuality();
        QCOMPARE(drag.imageScale, 0.5);
        QVERIFY(drag.stepFactor >= 1.0);
        bool dragMeasured = false;
        for (const QualityPoint& p : front->points) {
            dragMeasured =
                dragMeasured || (p.setting.interpolation == fast->setting.interpolation &&
                                 p.setting.step == fast->setting.step * drag.stepFactor);
        }
        QVERIFY2(dragMeasured, qPrintable(controls.qualityStatus()));

        controls.qualityPicker()->setCurrentIndex(3); // Best: from the same front, at once
        QCOMPARE(chosen.size(), 2);
        const QualityPoint* best = pointOf(*front, view);
        QVERIFY(best && best->pareto);
        QVERIFY2(best->psnrDb >= fast->psnrDb, qPrintable(controls.qualityStatus()));
        QVERIFY2(best->ms >= fast->ms, qPrintable(controls.qualityStatus()));

        // A larger view: each frame costs more, so Best may step down, never up.
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        const QString smallStatus = controls.qualityStatus();
        view.resize(640, 512);
        QVERIFY2(controls.qualityStatus() != smallStatus, qPrintable(smallStatus));
        const QualityPoint* bestLarge = pointOf(*front, view);
        QVERIFY(bestLarge && bestLarge->pareto);
        QVERIFY2(bestLarge->psnrDb <= best->psnrDb, qPrintable(controls.qualityStatus()));
        view.resize(160, 128);
        QCOMPARE(pointOf(*front, view), best);

        controls.qualityPicker()->setCurrentIndex(4); // Target time
        controls.qualityTarget()->setValue(1);
        const TimeModel time =
            front->timeModel(view.description().width, view.description().height);
        bool reachable = false;
        for (const QualityPoint& p : front->points) {
            reachable = reachable || (p.pareto && p.setting.shading && time.predict(p.ms) <= 1.0);
        }
        if (!reachable) {
            QVERIFY2(controls.qualityStatus().contains("fastest"),
                     qPrintable(controls.qualityStatus()));
        }

        controls.qualityPicker()->setCurrentIndex(0); // Manual: the view's own sampling
        QCOMPARE(view.sampling().step, 0.75);
        QCOMPARE(controls.dragQuality().stepFactor, InteractiveQuality{}.stepFactor);
        QVERIFY(controls.qualityStatus().isEmpty());

        // Another panel (a new session) finds the front in the cache dir.
        VolumeViewControls again(&view);
        again.setQualityCacheDir(cache_.path());
        QSignalSpy chosenAgain(&again, &VolumeViewControls::qualityChosen);
        again.qualityPicker()->setCurrentIndex(3);
        QCOMPARE(chosenAgain.size(), 1);
        QCOMPARE(pointOf(*front, view), best);
        QCOMPARE(QDir(cache_.path()).entryList({"quality-front-*.csv"}).size(), 1);
    }

    void glViewMeasuresOnTheGpu() {
        VolumeView view(nullptr, VolumeView::Backend::Gpu);
        view.resize(160, 128);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        if (view.backend() != VolumeView::Backend::Gpu) {
            QSKIP(qPrintable("the view is not on the GPU: " + view.notice()));
        }
        view.setVolume(std::make_shared<Volume>(
            test::makeVolume({40, 36, 32}, test::blobs, VoxelType::Int16)));
        view.setTransferFunction(test::rampTf(false));
        QTemporaryDir cache;
        VolumeViewControls controls(&view);
        controls.setQualityCacheDir(cache.path());
        QSignalSpy chosen(&controls, &VolumeViewControls::qualityChosen);
        controls.qualityPicker()->setCurrentIndex(2); // Balanced
        QVERIFY(chosen.wait(240000));
        QVERIFY2(!controls.qualityStatus().contains("on the CPU"),
                 qPrintable(controls.qualityStatus()));
        const auto front =
            loadFront(cache.path().toStdString(), frontKey(view.description(), "gl"));
        QVERIFY2(front, "the GL front is in the cache dir");
        const QualityPoint* balanced = pointOf(*front, view);
        QVERIFY2(balanced && balanced->pareto, qPrintable(controls.qualityStatus()));
    }
};

int main(int argc, char** argv) {
    if (const int status = lucent::test::relaunchUnderXvfbWhenHeadless(argc, argv); status >= 0) {
        return status;
    }
    QSurfaceFormat::setDefaultFormat(VolumeView::surfaceFormat());
    QApplication app(argc, argv);
    TestQualityPicker test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_quality_picker.moc"
