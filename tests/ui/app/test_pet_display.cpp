// PET series in the workstation, opened as a user opens them (File > Open: MainWindow's
// loader; the viewport grid's SeriesLibrary): a PET made from the real CT with DCMTK is
// shown in SUVbw (values at voxels and at the cursor against the stored activity times the
// factor by hand, the 0 to 6 SUV window, "SUVbw" in the corner text), its ellipse ROI reports
// SUVmax, SUVmean and SUVpeak equal to suvStatistics over the ellipsoid's voxels found by
// hand; without PatientWeight it is shown in Bq/mL and the user is told why, naming
// PatientWeight (0010,1030). Offscreen.
#include <QApplication>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QTest>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <tuple>

#include "core/io/Catalog.h"
#include "core/io/DisplayedSeries.h"
#include "core/pet/SuvStatistics.h"
#include "tests/support/OffscreenPlatform.h"
#include "tests/support/PetFromCt.h"
#include "tests/support/RealData.h"
#include "ui/app/MainWindow.h"
#include "ui/fusion/SliceFusion.h"
#include "ui/fusion/ViewportFusion.h"
#include "ui/mpr/MeasurementPainter.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SeriesMeasurements.h"
#include "ui/mpr/SliceOverlay.h"
#include "ui/mpr/SliceView.h"
#include "ui/viewports/GridShape.h"
#include "ui/viewports/SeriesLibrary.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportWorkspace.h"

using namespace lucent;
using namespace lucent::test;

namespace {

const char* const kCt = "dcm_qa_ct/Philips_S21570/S2010";

// PetHeader's 75.5 kg, 370 MBq of 18F injected 3900 s before the scan.
double handFactor() {
    return 75500.0 / (370e6 * std::pow(2.0, -3900.0 / 6586.2));
}

bool near(double got, double want, double relative = 1e-6, double absolute = 0.0) {
    return std::abs(got - want) <= relative * std::abs(want) + absolute;
}

using VoxelSet = std::set<std::tuple<int, int, int>>;

// The voxels whose centres lie in the ellipsoid an ellipse on `plane` spans (its semi-axes
// along u and v, the shorter along the normal), by brute force over the whole volume.
std::vector<glm::ivec3> ellipsoidByHand(const VolumeGeometry& g, const SlicePlane& plane,
                                        const EllipseRoi& e) {
    const glm::dvec3 n = glm::normalize(glm::cross(plane.u, plane.v));
    const glm::dvec3 c = e.centre - n * glm::dot(e.centre - plane.centre, n);
    const double across = std::min(e.radiusU, e.radiusV);
    std::vector<glm::ivec3> out;
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                const glm::dvec3 d = g.toPatient(glm::dvec3(i, j, k)) - c;
                const double a = glm::dot(d, plane.u) / e.radiusU;
                const double b = glm::dot(d, plane.v) / e.radiusV;
                const double h = glm::dot(d, n) / across;
                if (a * a + b * b + h * h <= 1.0) {
                    out.emplace_back(i, j, k);
                }
            }
        }
    }
    return out;
}

VoxelSet toSet(const std::vector<glm::ivec3>& voxels) {
    VoxelSet out;
    for (const glm::ivec3& v : voxels) {
        out.emplace(v.x, v.y, v.z);
    }
    return out;
}

} // namespace

class TestPetDisplay : public QObject {
    Q_OBJECT
    QTemporaryDir settingsDir_;
    QTemporaryDir suvDir_;
    QTemporaryDir noWeightDir_;
    PetSeries suv_;
    PetSeries noWeight_;
    std::unique_ptr<MainWindow> window_;

    // Opens a folder as File > Open does and waits for it.
    std::shared_ptr<const Volume> open(const QString& folder) {
        QSignalSpy finished(window_.get(), &MainWindow::loadFinished);
        window_->openPath(folder);
        if (!QTest::qWaitFor([&] { return finished.count() == 1; }, 60000) ||
            !finished.at(0).at(0).toBool()) {
            return nullptr;
        }
        return window_->volume();
    }

    // The series as the viewport grid's library loads it.
    SeriesSession* session(const QString& folder) {
        SeriesLibrary* library = window_->workspace()->library();
        QSignalSpy ready(library, &SeriesLibrary::ready);
        library->request(folder, {});
        return QTest::qWaitFor([&] { return ready.count() == 1; }, 60000)
                   ? ready.at(0).at(2).value<SeriesSession*>()
                   : nullptr;
    }

    // Voxels at three slices, each equal to the stored activity times `factor`.
    void checkVoxels(const Volume& volume, const PetSeries& pet, double factor) {
        const SeriesEntry entry = scanPath(pet.files.front().parent_path()).series.front();
        int nonZero = 0;
        for (const int k : {0, 13, volume.dims().z - 1}) {
            const auto file = entry.slices[static_cast<std::size_t>(k)].file;
            for (const auto& [i, j] : {std::pair{256, 256}, {210, 290}, {120, 240}, {330, 180}}) {
                const double want = storedActivity(pet, file, i, j) * factor;
                const double got = volume.value(i, j, k);
                nonZero += want != 0.0 ? 1 : 0;
                QVERIFY2(near(got, want) || (want == 0.0 && got == 0.0),
                         qPrintable(QString("slice %1 (%2, %3): %4, by hand %5")
                                        .arg(k)
                                        .arg(i)
                                        .arg(j)
                                        .arg(got)
                                        .arg(want)));
            }
        }
        QVERIFY(nonZero >= 6);
    }

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        qRegisterMetaType<SeriesSession*>(); // SeriesLibrary::ready's, for QSignalSpy
        QStandardPaths::setTestModeEnabled(true);
        QCoreApplication::setOrganizationName(QStringLiteral("lucent-test"));
        QCoreApplication::setApplicationName(QStringLiteral("test_pet_display"));
        QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, settingsDir_.path());
        suv_ = writePetFromCt(kRealData / kCt, suvDir_.path().toStdString(), {});
        PetHeader header;
        header.patientWeight.clear();
        noWeight_ = writePetFromCt(kRealData / kCt, noWeightDir_.path().toStdString(), header);
    }

    void init() {
        QSettings().clear();
        window_ = std::make_unique<MainWindow>();
        window_->resize(1100, 800);
        window_->show();
        QVERIFY(QTest::qWaitForWindowExposed(window_.get()));
    }

    void cleanup() { window_.reset(); }

    void shownInSuv() {
        const std::shared_ptr<const Volume> volume = open(suvDir_.path());
        QVERIFY(volume != nullptr);
        QVERIFY(volume->pet && volume->pet->inSuv());
        QVERIFY(near(volume->pet->suvFactor, handFactor(), 1e-12));
        checkVoxels(*volume, suv_, handFactor());
        QCOMPARE(window_->cursor()->windowCenter(), 3.0);
        QCOMPARE(window_->cursor()->windowWidth(), 6.0);
        QVERIFY(seriesOverlayLines(*volume).contains(QStringLiteral("SUVbw")));

        // The value at the cursor: the SUV interpolated at the pixel's point, which is the
        // activity interpolated there times the factor.
        const Volume activity = loadSeries(scanPath(suvDir_.path().toStdString()).series.front());
        SliceView* axial = window_->view(Orientation::Axial);
        const SlicePlane plane = axial->plane();
        const glm::dvec2 centre = glm::round(plane.pixelOf(window_->cursor()->point()));
        for (const glm::dvec2 offset :
             {glm::dvec2(0, 0), glm::dvec2(-23, 11), glm::dvec2(31, -17)}) {
            const glm::dvec2 px = centre + offset;
            const glm::dvec3 p = plane.pointAt(px.x, px.y);
            const double want =
                sampleAt(activity, activity.geometry().toIndex(p)) * volume->pet->suvFactor;
            const double got = axial->valueAt(QPointF(px.x + 0.5, px.y + 0.5));
            QVERIFY2(near(got, want, 1e-5, 1e-7), qPrintable(QString("at pixel %1, %2: %3, want %4")
                                                                 .arg(px.x)
                                                                 .arg(px.y)
                                                                 .arg(got)
                                                                 .arg(want)));
        }

        // PET is read in inverted grey: the image's pixel is the window's grey turned over.
        QVERIFY(window_->cursor()->invertedGrey());
        const QImage image = axial->image();
        QCOMPARE(image.devicePixelRatio(), 1.0);
        for (const glm::dvec2 offset : {glm::dvec2(0, 0), glm::dvec2(-23, 11)}) {
            const glm::dvec2 px = centre + offset;
            const double value = axial->valueAt(QPointF(px.x + 0.5, px.y + 0.5));
            QCOMPARE(qGray(image.pixel(int(px.x), int(px.y))), 255 - windowToGrey(value, 3.0, 6.0));
        }

        // The grid loads it the same way.
        SeriesSession* s = session(suvDir_.path());
        QVERIFY(s != nullptr && s->volume());
        QVERIFY(s->volume()->pet && s->volume()->pet->inSuv());
        checkVoxels(*s->volume(), suv_, handFactor());
        QCOMPARE(s->cursor()->windowWidth(), 6.0);
        QVERIFY(s->cursor()->invertedGrey());
    }

    // Fused over the CT in the grid, the PET's colour bar is in SUVbw.
    void fusedOverCtIsInSuvbw() {
        ViewportWorkspace workspace;
        workspace.resize(900, 500);
        workspace.grid()->setShape(*gridShape(QStringLiteral("1x2")));
        workspace.show();
        ViewportFusion fusion(&workspace);
        Viewport* left = workspace.grid()->viewports()[0];
        Viewport* right = workspace.grid()->viewports()[1];
        auto pet = std::make_shared<Volume>(
            loadDisplayedSeries(scanPath(suvDir_.path().toStdString()).series.front()));
        QVERIFY(pet->pet && pet->pet->inSuv());
        workspace.grid()->setActiveViewport(right);
        workspace.showVolume(pet, QStringLiteral("pet"), QString());
        workspace.grid()->setActiveViewport(left);
        workspace.showVolume(std::make_shared<Volume>(loadPath(kRealData / kCt)),
                             QStringLiteral("ct"), QString());
        QVERIFY(QTest::qWaitForWindowExposed(&workspace));
        QString why;
        QVERIFY2(fusion.fuse(left, right->session(), &why), qPrintable(why));
        QCOMPARE(left->sliceView()->fusion().layer()->unit, QStringLiteral("SUVbw"));
    }

    // An ellipse on the axial view: SUVmax, SUVmean and SUVpeak over the ellipsoid it spans,
    // as suvStatistics gives them for the voxels found by hand, in the list's and the
    // overlay's text, and the plane statistics in SUVbw.
    void ellipseReportsSuvs() {
        const std::shared_ptr<const Volume> volume = open(suvDir_.path());
        QVERIFY(volume != nullptr);
        SeriesMeasurements* measurements = window_->measurements();
        QVERIFY(measurements != nullptr);
        const SlicePlane plane = window_->view(Orientation::Axial)->plane();
        const EllipseRoi roi{plane.pointAt(0.5 * plane.width - 14.0, 0.5 * plane.height + 9.0),
                             13.5, 8.25};
        const std::uint64_t id = measurements->add(makeEllipseMeasurement(plane, roi));
        const Measurement& m = *measurements->find(id);
        QCOMPARE(m.unit, std::string("SUVbw"));
        QVERIFY(m.suv.has_value());

        const std::vector<glm::ivec3> voxels = ellipsoidByHand(volume->geometry(), plane, roi);
        QVERIFY(voxels.size() > 200);
        QVERIFY(toSet(voxels) ==
                toSet(ellipseSuvRegion(volume->geometry(), m.plane, measurementEllipse(m))));
        const SuvStatistics byHand = suvStatistics(*volume, voxels);
        QCOMPARE(m.suv->voxels, byHand.voxels);
        QCOMPARE(m.suv->max, byHand.max);
        QVERIFY(near(m.suv->mean, byHand.mean, 1e-12));
        QCOMPARE(m.suv->peak, byHand.peak);
        qInfo("SUVmax %.4f SUVmean %.4f SUVpeak %.4f over %zu voxels", byHand.max, byHand.mean,
              byHand.peak, byHand.voxels);
        // The region holds uptake; the 1 mL spheres reach beyond it (hotter voxels around).
        QVERIFY(byHand.max > byHand.mean && byHand.mean > 0.0 && byHand.peak > 0.0);

        const QString overlay = measurementOverlayText(m);
        for (const QString& line :
             {QStringLiteral("SUVmax %1").arg(byHand.max, 0, 'f', 2),
              QStringLiteral("SUVpeak %1").arg(byHand.peak, 0, 'f', 2),
              QStringLiteral("SUVmean %1").arg(byHand.mean, 0, 'f', 2), QStringLiteral("SUVbw")}) {
            QVERIFY2(overlay.contains(line), qPrintable(overlay));
        }
        QVERIFY(QString::fromStdString(measurementValueText(m)).startsWith("SUVmax "));
    }

    void missingWeightShowsBqPerMl() {
        const std::shared_ptr<const Volume> volume = open(noWeightDir_.path());
        QVERIFY(volume != nullptr);
        QVERIFY(volume->pet && !volume->pet->inSuv());
        QCOMPARE(volume->pet->unit(), std::string("Bq/mL"));
        checkVoxels(*volume, noWeight_, 1.0);
        const QString told = window_->statusBar()->currentMessage();
        QVERIFY2(told.contains(QStringLiteral("PatientWeight (0010,1030)")) &&
                     told.contains(QStringLiteral("Bq/mL")),
                 qPrintable(told));
        QVERIFY(seriesOverlayLines(*volume).contains(QStringLiteral("Bq/mL (not SUVbw)")));
        QVERIFY(window_->cursor()->windowWidth() != 6.0);

        // An ellipse has its statistics in Bq/mL and no SUVs.
        const SlicePlane plane = window_->view(Orientation::Axial)->plane();
        const EllipseRoi roi{plane.pointAt(0.5 * plane.width, 0.5 * plane.height), 10.0, 10.0};
        const std::uint64_t id = window_->measurements()->add(makeEllipseMeasurement(plane, roi));
        QCOMPARE(window_->measurements()->find(id)->unit, std::string("Bq/mL"));
        QVERIFY(!window_->measurements()->find(id)->suv);

        // The grid tells it once too, when it loads the series.
        QSignalSpy messages(window_->workspace(), &ViewportWorkspace::message);
        SeriesSession* s = session(noWeightDir_.path());
        QVERIFY(s != nullptr && s->volume() && !s->volume()->pet->inSuv());
        QTRY_VERIFY(!messages.isEmpty());
        QVERIFY2(messages.at(0).at(0).toString().contains("PatientWeight (0010,1030)"),
                 qPrintable(messages.at(0).at(0).toString()));
        session(noWeightDir_.path()); // loaded already: not told again
        QCoreApplication::processEvents();
        QCOMPARE(messages.count(), 1);
    }
};

int main(int argc, char** argv) {
    lucent::test::useOffscreenPlatform();
    QApplication app(argc, argv);
    TestPetDisplay test;
    return QTest::qExec(&test, argc, argv);
}

#include "test_pet_display.moc"
