// The reconstruction filters: exact answers for polynomial fields.
#include <QTest>

#include <random>

#include "core/raycast/BSplinePrefilter.h"
#include "core/raycast/VolumeFields.h"

using namespace lucent;

namespace {

Volume fieldVolume(glm::ivec3 dims, const std::function<double(double, double, double)>& f) {
    VolumeGeometry g;
    g.dims = dims;
    Volume v(g, VoxelType::Float32);
    auto out = v.voxels<float>();
    for (int k = 0; k < dims.z; ++k) {
        for (int j = 0; j < dims.y; ++j) {
            for (int i = 0; i < dims.x; ++i) {
                out[v.linearIndex(i, j, k)] = float(f(i, j, k));
            }
        }
    }
    return v;
}

} // namespace

class TestVolumeFields : public QObject {
    Q_OBJECT
private slots:
    void trilinearReproducesLinearFields() {
        const auto f = [](double x, double y, double z) {
            return 3.0 * x - 2.0 * y + 0.5 * z + 7.0;
        };
        const Volume v = fieldVolume({9, 8, 7}, f);
        const LinearField<double, float> field{
            Grid<double, float>(v.voxels<float>().data(), v.dims())};
        std::mt19937 rng(1);
        std::uniform_real_distribution<double> ux(0, 8), uy(0, 7), uz(0, 6);
        for (int n = 0; n < 200; ++n) {
            const glm::dvec3 p(ux(rng), uy(rng), uz(rng));
            QVERIFY(std::abs(field.value(p) - f(p.x, p.y, p.z)) < 1e-4);
        }
        const glm::dvec3 g = field.gradient({4.3, 3.2, 2.9});
        QVERIFY(glm::length(g - glm::dvec3(3.0, -2.0, 0.5)) < 1e-4);
    }

    void tricubicInterpolatesTheVoxels() {
        std::mt19937 rng(2);
        std::uniform_real_distribution<double> u(-1000, 1000);
        const Volume v = fieldVolume({12, 10, 9}, [&](double, double, double) { return u(rng); });
        const auto c = bsplineCoefficients<double>(v);
        const CubicField<double> field{Grid<double, double>(c.data(), v.dims())};
        for (int k = 0; k < 9; ++k) {
            for (int j = 0; j < 10; ++j) {
                for (int i = 0; i < 12; ++i) {
                    QVERIFY2(std::abs(field.value({i, j, k}) - v.value(i, j, k)) < 1e-6,
                             qPrintable(QString("(%1,%2,%3)").arg(i).arg(j).arg(k)));
                }
            }
        }
    }

    void tricubicReproducesLinearAndQuadraticFields_data() {
        QTest::addColumn<int>("degree");
        QTest::newRow("linear") << 1;
        QTest::newRow("quadratic") << 2;
    }
    void tricubicReproducesLinearAndQuadraticFields() {
        QFETCH(int, degree);
        const auto f = [&](double x, double y, double z) {
            const double lin = 2.0 * x - 1.5 * y + 0.75 * z + 3.0;
            return degree == 1 ? lin : lin + 0.05 * x * x - 0.03 * y * z + 0.02 * z * z;
        };
        const auto grad = [&](double x, double y, double z) {
            glm::dvec3 g(2.0, -1.5, 0.75);
            if (degree == 2) {
                g += glm::dvec3(0.1 * x, -0.03 * z, -0.03 * y + 0.04 * z);
            }
            return g;
        };
        // Mirror boundaries bend polynomials near the faces; the effect decays as
        // (2 - sqrt 3)^distance, below 1e-9 of the field 16 voxels in.
        const glm::ivec3 dims(48, 48, 48);
        const Volume v = fieldVolume(dims, f);
        const auto c = bsplineCoefficients<double>(v);
        const CubicField<double> field{Grid<double, double>(c.data(), dims)};
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> u(16.0, 31.0);
        for (int n = 0; n < 300; ++n) {
            const glm::dvec3 p(u(rng), u(rng), u(rng));
            const double err = std::abs(field.value(p) - f(p.x, p.y, p.z));
            QVERIFY2(
                err < 1e-5,
                qPrintable(QString("error %1 at %2,%3,%4").arg(err).arg(p.x).arg(p.y).arg(p.z)));
            QVERIFY(glm::length(field.gradient(p) - grad(p.x, p.y, p.z)) < 1e-5);
        }
    }

    void nearestTakesTheClosestVoxel() {
        const Volume v = fieldVolume(
            {4, 4, 4}, [](double x, double y, double z) { return x + 10 * y + 100 * z; });
        const NearestField<float, float> field{
            Grid<float, float>(v.voxels<float>().data(), v.dims())};
        QCOMPARE(field.value({1.4f, 2.6f, 0.2f}), 31.0f);
        QCOMPARE(field.value({-3.0f, 9.0f, 1.6f}), 230.0f); // clamped to the volume
    }
};

QTEST_APPLESS_MAIN(TestVolumeFields)
#include "test_volume_fields.moc"
