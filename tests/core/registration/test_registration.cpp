// registerRigid on the real 28-slice CT (512x512x28, 0.45 x 0.45 x 5 mm) against copies of
// it resampled (trilinear) under known rigid and affine transforms: the target registration
// error over the points of a grid inside the body; an MR-like (non-monotonic) remapping
// through Mattes MI; the affine stage; the start from a shared Frame of Reference; noise,
// which must end in a RegistrationError; cancellation (in either stage) and progress.
#include <QTest>

#include <chrono>
#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "core/io/Catalog.h"
#include "core/registration/Registration.h"
#include "tests/support/KnownTransform.h"
#include "tests/support/RealData.h"

using namespace lucent;
using test::bodyGrid;
using test::resampled;
using test::rigidAbout;
using test::Tre;
using test::treOf;

namespace {

constexpr const char* kCt = "dcm_qa_ct/Philips_S21570/S2010";
const std::string kNewFrame = "1.2.826.0.1.3680043.2.1143.29.1";

// The CT cut to i in [i0, i0 + ni), j in [j0, j0 + nj), every slice: the same patient
// coordinates (and Frame of Reference), another box and so another geometric centre.
Volume cropped(const Volume& v, int i0, int ni, int j0, int nj) {
    VolumeGeometry g = v.geometry();
    g.origin = g.toPatient(glm::dvec3(i0, j0, 0));
    g.dims = glm::ivec3(ni, nj, v.dims().z);
    Volume out(g, VoxelType::Float32);
    out.modality = v.modality;
    out.frameOfReferenceUid = v.frameOfReferenceUid;
    std::span<float> voxels = out.voxels<float>();
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < nj; ++j) {
            for (int i = 0; i < ni; ++i) {
                voxels[out.linearIndex(i, j, k)] = static_cast<float>(v.value(i0 + i, j0 + j, k));
            }
        }
    }
    return out;
}

double identityMap(double hu) {
    return hu;
}

} // namespace

class TestRegistration : public QObject {
    Q_OBJECT
    Volume ct_;
    std::vector<glm::dvec3> grid_;

    void checkKnown(const glm::dvec3& degrees, const glm::dvec3& shift, bool mr,
                    RegistrationOptions::Metric metric, double maxTre) {
        const glm::dmat4 truth = rigidAbout(volumeCentre(ct_.geometry()), degrees, shift);
        const Volume moving = mr ? resampled(ct_, truth, test::mrLike, "MR", kNewFrame)
                                 : resampled(ct_, truth, identityMap, "CT", kNewFrame);
        RegistrationOptions options;
        options.metric = metric;
        int calls = 0;
        if (qEnvironmentVariableIsSet("REG_TRACE")) {
            options.onProgress = [&](double f, double m) {
                if (calls++ % 10 == 0)
                    qInfo("  %.3f %.4f", f, m);
            };
        }
        RegistrationResult r;
        try {
            r = registerRigid(ct_, moving, options);
        } catch (const std::exception& e) {
            QFAIL(e.what());
        }
        const Tre tre = treOf(grid_, truth, r.fixedToMoving);
        qInfo("%s: TRE mean %.3f max %.3f mm over %zu points; metric %.4f, %d iterations, "
              "%.1f s, %s",
              metricName(metric), tre.mean, tre.max, grid_.size(), r.metric, r.iterations,
              r.seconds, r.reason.c_str());
        QVERIFY2(tre.max < maxTre, qPrintable(QString("max TRE %1 mm").arg(tre.max)));
        // Another Frame of Reference: started from the geometric centres; rigid only.
        QCOMPARE(r.initialisation, RegistrationOptions::Initialisation::Centres);
        QVERIFY(!r.affine);
        QCOMPARE(r.rigidFixedToMoving, r.fixedToMoving);
    }

private slots:
    void initTestCase() {
        REQUIRE_DATA(kCt);
        const Catalog catalog = scanPath(test::kRealData / kCt);
        QVERIFY(catalog.defaultEntry() != nullptr);
        ct_ = loadSeries(*catalog.defaultEntry());
        QCOMPARE(ct_.dims(), glm::ivec3(512, 512, 28));
        grid_ = bodyGrid(ct_);
        qInfo("TRE grid: %zu points inside the body; spacing %.3f %.3f %.3f", grid_.size(),
              ct_.geometry().spacing.x, ct_.geometry().spacing.y, ct_.geometry().spacing.z);
        QVERIFY(grid_.size() > 200);
    }

    void knownTransform_data() {
        QTest::addColumn<glm::dvec3>("degrees");
        QTest::addColumn<glm::dvec3>("shift");
        QTest::newRow("shift 12,-8,5 mm") << glm::dvec3(0.0) << glm::dvec3(12.0, -8.0, 5.0);
        QTest::newRow("z 10 deg, 30 mm") << glm::dvec3(0, 0, 10) << glm::dvec3(30.0, 0.0, 0.0);
        QTest::newRow("x 3 y -2 z -6 deg, -10,20,-4 mm")
            << glm::dvec3(3, -2, -6) << glm::dvec3(-10.0, 20.0, -4.0);
    }
    void knownTransform() {
        QFETCH(glm::dvec3, degrees);
        QFETCH(glm::dvec3, shift);
        checkKnown(degrees, shift, false, RegistrationOptions::Metric::MutualInformation, 0.5);
    }

    void meanSquares() {
        checkKnown({0, 0, 5}, {-6.0, 9.0, 0.0}, false, RegistrationOptions::Metric::MeanSquares,
                   0.5);
    }

    void mrLikeContrast() {
        checkKnown({2, 0, 7}, {8.0, -15.0, 3.0}, true,
                   RegistrationOptions::Metric::MutualInformation, 1.0);
    }

    void noiseIsRefused_data() {
        QTest::addColumn<int>("metric");
        QTest::newRow("Mattes MI") << int(RegistrationOptions::Metric::MutualInformation);
        // Not mean squares: its check is coarse (Registration.h), noise passes it.
    }
    void noiseIsRefused() {
        QFETCH(int, metric);
        Volume noise(ct_.geometry(), VoxelType::Float32);
        std::mt19937 random(7);
        std::uniform_real_distribution<float> uniform(-1000.0f, 1000.0f);
        for (float& v : noise.voxels<float>()) {
            v = uniform(random);
        }
        RegistrationOptions options;
        options.metric = RegistrationOptions::Metric(metric);
        try {
            const RegistrationResult r = registerRigid(ct_, noise, options);
            QFAIL(qPrintable(QString("registered noise: metric %1").arg(r.metric)));
        } catch (const RegistrationError& e) {
            qInfo("%s", e.what());
            QCOMPARE(QString::fromStdString(e.metric), QString(metricName(options.metric)));
            QVERIFY(QString(e.what()).contains(metricName(options.metric)));
            QVERIFY(QString(e.what()).contains("share no structure"));
        }
    }

    void uniformIsRefused() {
        Volume flat(ct_.geometry(), VoxelType::Int16);
        std::fill(flat.voxels<std::int16_t>().begin(), flat.voxels<std::int16_t>().end(), 40);
        QVERIFY_THROWS_EXCEPTION(RegistrationError, registerRigid(flat, ct_, {}));
    }

    void cancelAndProgress() {
        std::stop_source stop;
        RegistrationOptions options;
        options.stop = stop.get_token();
        int calls = 0;
        double lastFraction = -1.0;
        bool monotonic = true;
        options.onProgress = [&](double fraction, double) {
            monotonic = monotonic && fraction >= lastFraction && fraction <= 1.0;
            lastFraction = fraction;
            if (++calls == 5) {
                stop.request_stop();
            }
        };
        const auto start = std::chrono::steady_clock::now();
        QVERIFY_THROWS_EXCEPTION(RegistrationCancelled, registerRigid(ct_, ct_, options));
        QCOMPARE(calls, 5);
        QVERIFY(monotonic && lastFraction > 0.0);
        QVERIFY(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));
    }

    // A 4 % stretch along x, a shear, 5 degrees about z and 10 mm, in a new Frame of
    // Reference: the affine stage ends under 1 mm everywhere inside the body, where the
    // rigid stage (its start, which is what a rigid-only run gives) cannot.
    void affineStage() {
        const glm::dmat4 truth = test::affineAbout(volumeCentre(ct_.geometry()), {1.04, 1.0, 1.0},
                                                   0.03, 5.0, {10.0, -6.0, 0.0});
        const Volume moving = resampled(ct_, truth, identityMap, "CT", kNewFrame);
        RegistrationOptions options;
        options.affine = true;
        double lastFraction = 0.0;
        bool monotonic = true;
        options.onProgress = [&](double fraction, double) {
            monotonic = monotonic && fraction >= lastFraction && fraction <= 1.0;
            lastFraction = fraction;
        };
        RegistrationResult r;
        try {
            r = registerRigid(ct_, moving, options);
        } catch (const std::exception& e) {
            QFAIL(e.what());
        }
        const Tre affine = treOf(grid_, truth, r.fixedToMoving);
        const Tre rigid = treOf(grid_, truth, r.rigidFixedToMoving);
        qInfo("affine: TRE mean %.3f max %.3f mm (rigid stage: mean %.3f max %.3f); metric "
              "%.4f, %d iterations, %.1f s, %s",
              affine.mean, affine.max, rigid.mean, rigid.max, r.metric, r.iterations, r.seconds,
              r.reason.c_str());
        QVERIFY(r.affine);
        QCOMPARE(r.initialisation, RegistrationOptions::Initialisation::Centres);
        QVERIFY2(affine.max < 1.0, qPrintable(QString("max TRE %1 mm").arg(affine.max)));
        QVERIFY(affine.mean < 0.5 * rigid.mean && affine.max < rigid.max);
        QVERIFY(monotonic && lastFraction > 0.6); // the affine stage's share: 2 of 5 levels
    }

    // The CT against a crop of itself that keeps its Frame of Reference: Auto starts from
    // the identity (the scanner's frame), where the anatomy already matches, not from the
    // two boxes' centres 48 mm apart. The first progress report gives the metric at the start
    // (the coarsest level, the same samples for both starts).
    void sameFrameOfReference() {
        QVERIFY(!ct_.frameOfReferenceUid.empty());
        const Volume crop = cropped(ct_, 0, 320, 96, 416);
        const glm::dvec3 apart = volumeCentre(crop.geometry()) - volumeCentre(ct_.geometry());
        QVERIFY(glm::length(apart) > 40.0);
        RegistrationOptions options;
        double atStart = 0.0;
        int calls = 0;
        options.onProgress = [&](double, double metric) {
            atStart = calls++ == 0 ? metric : atStart;
        };
        const RegistrationResult r = registerRigid(ct_, crop, options);
        const double identityStart = atStart;
        const Tre tre = treOf(grid_, glm::dmat4(1.0), r.fixedToMoving);
        qInfo("same Frame of Reference: %s, MI at the start %.3f; TRE mean %.3f max %.3f mm, "
              "%d iterations, %.1f s",
              initialisationName(r.initialisation), identityStart, tre.mean, tre.max, r.iterations,
              r.seconds);
        QCOMPARE(r.initialisation, RegistrationOptions::Initialisation::FrameOfReference);
        QVERIFY2(tre.max < 0.1, qPrintable(QString("max TRE %1 mm").arg(tre.max)));

        // Centres asked for: one iteration a level from the centres' offset, far from the
        // anatomy (so far that the result is refused; only the start matters here).
        options.initialisation = RegistrationOptions::Initialisation::Centres;
        options.maxIterations = 1;
        calls = 0;
        try {
            registerRigid(ct_, crop, options);
        } catch (const RegistrationError& e) {
            qInfo("centres, one iteration a level: %s", e.what());
        }
        qInfo("centres: MI at the start %.3f", atStart);
        QCOMPARE(calls, 3);
        QVERIFY(atStart > 0.5 * identityStart); // Mattes MI: negative, lower is better
    }

    // Cancelled in the affine stage: after the rigid stage's fraction, no more progress.
    void cancelInAffineStage() {
        std::stop_source stop;
        RegistrationOptions options;
        options.affine = true;
        options.levels = 1; // one level per stage: the rigid stage has the first half
        options.stop = stop.get_token();
        int affineCalls = 0;
        int afterStop = 0;
        options.onProgress = [&](double fraction, double) {
            afterStop += stop.stop_requested() ? 1 : 0;
            if (fraction > 0.5 && ++affineCalls == 3) {
                stop.request_stop();
            }
        };
        const auto start = std::chrono::steady_clock::now();
        QVERIFY_THROWS_EXCEPTION(RegistrationCancelled, registerRigid(ct_, ct_, options));
        QCOMPARE(affineCalls, 3);
        QCOMPARE(afterStop, 0);
        QVERIFY(std::chrono::steady_clock::now() - start < std::chrono::seconds(20));
    }

    void badOptionsNameTheField() {
        RegistrationOptions options;
        options.levels = 4;
        try {
            registerRigid(ct_, ct_, options);
            QFAIL("levels 4 accepted");
        } catch (const std::invalid_argument& e) {
            QVERIFY2(QString(e.what()).contains("options.levels is 4"), e.what());
        }
        options = {};
        options.samplesPerLevel = 10;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, registerRigid(ct_, ct_, options));
    }
};

QTEST_GUILESS_MAIN(TestRegistration)
#include "test_registration.moc"
