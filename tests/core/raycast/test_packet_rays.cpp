// The packet kernel's ray setup against the scalar one, lane by lane and bit
// for bit: raySpan's samples, the lattice in double and in float.
#include <QTest>

#include <cstring>
#include <random>

#include "core/raycast/PacketDvrKernel.h"
#include "core/raycast/PacketRays.h"

using namespace lucent;

namespace {

// Bit for bit (QCOMPARE on floating point is fuzzy).
template <class F> bool same(F a, F b) {
    return std::memcmp(&a, &b, sizeof(F)) == 0;
}

} // namespace

class TestPacketRays : public QObject {
    Q_OBJECT
private slots:
    void startRaysIsRaySpanPerLane() {
        if (!packetKernelSupported()) {
            QSKIP("this CPU has no AVX2");
        }
        std::mt19937 rng(5);
        std::uniform_real_distribution<double> u(-1.0, 1.0);
        RaySetup<float> s;
        s.boxLo = glm::dvec3(0.0);
        s.boxHi = glm::dvec3(39.0, 29.0, 19.0);
        int hits = 0, flat = 0;
        for (int trial = 0; trial < 2000; ++trial) {
            s.dt = 0.25 + 0.5 * (u(rng) + 1.0);
            const bool clip = trial % 3 == 0;
            s.clipLo = clip ? glm::dvec3(5.5, 2.0, 3.25) : s.boxLo;
            s.clipHi = clip ? glm::dvec3(30.0, 29.0, 12.5) : s.boxHi;
            // Eyes outside and inside the box; directions along axes now and then.
            const glm::dvec3 o = trial % 4 == 0
                                     ? glm::dvec3(20.0, 15.0, 10.0) + 5.0 * u(rng)
                                     : glm::dvec3(20.0, -60.0, 10.0) +
                                           glm::dvec3(30 * u(rng), 20 * u(rng), 15 * u(rng));
            glm::dvec3 d[8], w[8];
            const int count = 1 + trial % 8;
            for (int r = 0; r < count; ++r) {
                d[r] = glm::dvec3(0.3 * u(rng), 1.0, 0.3 * u(rng));
                if (rng() % 5 == 0) {
                    d[r][rng() % 3] = rng() % 2 == 0 ? 0.0 : 1e-16;
                    ++flat;
                }
                w[r] = glm::normalize(d[r]);
            }
            packet::PacketRays rays;
            packet::startRays(s, o, d, w, count, rays);
            for (int r = 0; r < 8; ++r) {
                RaySpan span;
                const bool hit =
                    r < count && raySpan(s, o, d[r], span) && span.nFirst <= span.nLast;
                QCOMPARE((rays.active >> r & 1) != 0, hit);
                if (!hit) {
                    continue;
                }
                ++hits;
                QCOMPARE(rays.first[r], int(span.nFirst));
                QCOMPARE(rays.last[r], int(span.nLast));
                const glm::dvec3 entry = o + d[r] * span.t0, stride = d[r] * s.dt;
                for (int a = 0; a < 3; ++a) {
                    QVERIFY(same(rays.lattice.entry[a][r], entry[a]));
                    QVERIFY(same(rays.lattice.stride[a][r], stride[a]));
                    QVERIFY(same(rays.lattice.inverse[a][r],
                                 std::abs(stride[a]) > 1e-15 ? 1.0 / stride[a] : 0.0));
                    QVERIFY(same(rays.entry[a][r], float(entry[a])));
                    QVERIFY(same(rays.stride[a][r], float(stride[a])));
                    QVERIFY(same(rays.dir[a][r], float(w[r][a])));
                }
            }
        }
        QVERIFY2(hits > 2000 && flat > 500, qPrintable(QString("%1 %2").arg(hits).arg(flat)));
    }
};

QTEST_APPLESS_MAIN(TestPacketRays)
#include "test_packet_rays.moc"
