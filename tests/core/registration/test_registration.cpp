// registerRigid on the real 28-slice CT (512x512x28, 0.7 x 0.7 x 5 mm) against copies of it
// resampled (trilinear) under known rigid transforms: the target registration error over
// the points of a grid inside the body; an MR-like (non-monotonic) remapping through
// Mattes MI; noise, which must end in a RegistrationError; cancellation and progress.
#include <QTest>

#include <chrono>
#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "core/io/Catalog.h"
#include "core/registration/Registration.h"
#include "tests/support/RealData.h"

using namespace lucent;

namespace {

constexpr const char* kCt = "dcm_qa_ct/Philips_S21570/S2010";

// A rigid transform about the volume centre c: x -> c + t + R (x - c), R from rotations
// about x, then y, then z (degrees).
glm::dmat4 rigidAbout(const glm::dvec3& c, const glm::dvec3& degrees, const glm::dvec3& t) {
    glm::dmat4 r(1.0);
    r = glm::rotate(r, glm::radians(degrees.z), glm::dvec3(0, 0, 1));
    r = glm::rotate(r, glm::radians(degrees.y), glm::dvec3(0, 1, 0));
    r = glm::rotate(r, glm::radians(degrees.x), glm::dvec3(1, 0, 0));
    return glm::translate(glm::dmat4(1.0), c + t) * r * glm::translate(glm::dmat4(1.0), -c);
}

// Trilinear sample at a continuous index; `outside` beyond the voxel centres.
double trilinear(const Volume& v, const glm::dvec3& ijk, double outside) {
    const glm::ivec3 d = v.dims();
    if (ijk.x < 0 || ijk.y < 0 || ijk.z < 0 || ijk.x > d.x - 1 || ijk.y > d.y - 1 ||
        ijk.z > d.z - 1) {
        return outside;
    }
    const glm::ivec3 i0 = glm::min(glm::ivec3(glm::floor(ijk)), d - 2);
    const glm::dvec3 f = ijk - glm::dvec3(i0);
    double sum = 0.0;
    for (int n = 0; n < 8; ++n) {
        const glm::ivec3 o(n & 1, (n >> 1) & 1, (n >> 2) & 1);
        const double w = (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
        if (w != 0.0) {
            sum += w * v.value(i0.x + o.x, i0.y + o.y, i0.z + o.z);
        }
    }
    return sum;
}

// The anatomy of `fixed` moved by fixedToMoving, on fixed's grid, intensities through `map`:
// moving(y) = map(fixed(fixedToMoving^-1 y)); air (-1024 HU) outside.
template <class Map>
Volume resampled(const Volume& fixed, const glm::dmat4& fixedToMoving, Map map,
                 const std::string& modality) {
    Volume moving(fixed.geometry(), VoxelType::Float32);
    moving.modality = modality;
    const glm::dmat4 indexToFixedIndex = fixed.geometry().patientToIndex() *
                                         glm::inverse(fixedToMoving) *
                                         fixed.geometry().indexToPatient();
    const glm::ivec3 d = fixed.dims();
    std::span<float> out = moving.voxels<float>();
    for (int k = 0; k < d.z; ++k) {
        for (int j = 0; j < d.y; ++j) {
            for (int i = 0; i < d.x; ++i) {
                const glm::dvec3 src = glm::dvec3(indexToFixedIndex * glm::dvec4(i, j, k, 1.0));
                out[moving.linearIndex(i, j, k)] =
                    static_cast<float>(map(trilinear(fixed, src, -1024.0)));
            }
        }
    }
    return moving;
}

double identityMap(double hu) {
    return hu;
}

// MR-like and non-monotonic: air and bone dark, fat bright, soft tissue in between.
double mrLike(double hu) {
    return 1000.0 * std::exp(-std::pow((hu + 100.0) / 150.0, 2)) +
           500.0 * std::exp(-std::pow((hu - 40.0) / 80.0, 2)) + 20.0;
}

// The grid of the TRE: every 10 mm in x, y and z, over the fixed volume
// (two slices in from its ends), where the fixed CT is above -500 HU (inside the body).
std::vector<glm::dvec3> bodyGrid(const Volume& fixed) {
    std::vector<glm::dvec3> points;
    const VolumeGeometry& g = fixed.geometry();
    const glm::dvec3 step = glm::dvec3(10.0) / g.spacing;
    for (double k = 2; k <= g.dims.z - 3; k += step.z) {
        for (double j = 0; j < g.dims.y; j += step.y) {
            for (double i = 0; i < g.dims.x; i += step.x) {
                const glm::ivec3 n = glm::ivec3(glm::round(glm::dvec3(i, j, k)));
                if (fixed.value(n.x, n.y, n.z) > -500.0) {
                    points.push_back(g.toPatient(glm::dvec3(n)));
                }
            }
        }
    }
    return points;
}

struct Tre {
    double mean = 0.0;
    double max = 0.0;
};

Tre treOf(const std::vector<glm::dvec3>& points, const glm::dmat4& truth, const glm::dmat4& found) {
    Tre t;
    for (const glm::dvec3& p : points) {
        const double e = glm::length(glm::dvec3(truth * glm::dvec4(p, 1.0)) -
                                     glm::dvec3(found * glm::dvec4(p, 1.0)));
        t.mean += e / static_cast<double>(points.size());
        t.max = std::max(t.max, e);
    }
    return t;
}

} // namespace

class TestRegistration : public QObject {
    Q_OBJECT
    Volume ct_;
    std::vector<glm::dvec3> grid_;

    void checkKnown(const glm::dvec3& degrees, const glm::dvec3& shift, bool mr,
                    RegistrationOptions::Metric metric, double maxTre) {
        const glm::dmat4 truth = rigidAbout(volumeCentre(ct_.geometry()), degrees, shift);
        const Volume moving =
            mr ? resampled(ct_, truth, mrLike, "MR") : resampled(ct_, truth, identityMap, "CT");
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

    void affineIsNotYet() {
        RegistrationOptions options;
        options.affine = true;
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, registerRigid(ct_, ct_, options));
    }
};

QTEST_GUILESS_MAIN(TestRegistration)
#include "test_registration.moc"
