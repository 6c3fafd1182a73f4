// IceT's compositing of known premultiplied layers against a serial front-to-back
// blend and a serial depth test, on however many ranks mpirun starts.
#include <QTest>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "render/distributed/IceTCompositor.h"
#include "tests/distributed/MpiTestMain.h"

using namespace lucent;

namespace {

// Rank r's layer: a soft band whose place and colour depend on r; rank 2 (when
// there is one) draws nothing, as a rank whose bricks are all clipped away.
glm::vec4 layer(int r, int x, int y, int w, int h) {
    if (r == 2) {
        return glm::vec4(0.0f);
    }
    const float u = (float(x) + 0.5f) / float(w), v = (float(y) + 0.5f) / float(h);
    const float centre = 0.2f + 0.15f * float(r);
    const float a = std::clamp(0.9f - 3.0f * std::abs(u - centre) - 0.3f * v, 0.0f, 1.0f);
    const glm::vec3 colour(0.3f + 0.2f * float(r % 4), 1.0f - 0.2f * float(r % 5),
                           0.5f + 0.1f * float(r % 3));
    return glm::vec4(colour * a, a);
}

float depthOf(int r, int x, int y, int w, int h) {
    const float u = (float(x) + 0.5f) / float(w), v = (float(y) + 0.5f) / float(h);
    const float d =
        0.5f + 0.4f * std::sin(3.0f * u + 1.7f * float(r)) * std::cos(2.0f * v + float(r));
    return (x + y + r) % 7 == 0 ? 1.0f : d; // some pixels empty on each rank
}

} // namespace

class TestIceTCompositor : public QObject {
    Q_OBJECT

    Communicator comm_ = Communicator::world();

    std::vector<glm::vec4> myLayer(int w, int h) const {
        std::vector<glm::vec4> out(std::size_t(w) * h);
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                out[std::size_t(y) * w + x] = layer(comm_.rank(), x, y, w, h);
            }
        }
        return out;
    }

private slots:
    void blendEqualsSerialFrontToBack_data() {
        QTest::addColumn<int>("width");
        QTest::addColumn<int>("height");
        QTest::addColumn<int>("rotate");
        QTest::addColumn<bool>("reverse");
        QTest::newRow("96x96 rank order") << 96 << 96 << 0 << false;
        QTest::newRow("96x96 reversed") << 96 << 96 << 0 << true;
        QTest::newRow("37x23 rotated") << 37 << 23 << 1 << false;
        QTest::newRow("64x40 rotated reversed") << 64 << 40 << 2 << true;
    }
    void blendEqualsSerialFrontToBack() {
        QFETCH(int, width);
        QFETCH(int, height);
        QFETCH(int, rotate);
        QFETCH(bool, reverse);
        const int n = comm_.size();
        std::vector<int> order(static_cast<std::size_t>(n));
        std::iota(order.begin(), order.end(), 0);
        std::rotate(order.begin(), order.begin() + rotate % n, order.end());
        if (reverse) {
            std::reverse(order.begin(), order.end());
        }
        IceTCompositor icet(comm_);
        const std::vector<glm::vec4> mine = myLayer(width, height);
        const auto view = icet.blend(width, height, mine, order);
        const std::vector<glm::vec4> out(view.begin(), view.end());
        if (comm_.rank() != 0) {
            QVERIFY(out.empty());
            return;
        }
        QCOMPARE(int(out.size()), width * height);
        double worst = 0.0, total = 0.0;
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                glm::dvec4 acc(0.0);
                for (int r : order) {
                    acc += (1.0 - acc.a) * glm::dvec4(layer(r, x, y, width, height));
                }
                const glm::dvec4 got(out[std::size_t(y) * width + x]);
                for (int c = 0; c < 4; ++c) {
                    worst = std::max(worst, std::abs(got[c] - acc[c]));
                }
                total += acc.a;
            }
        }
        QVERIFY2(worst < 1e-5, qPrintable(QString("max error %1").arg(worst)));
        QVERIFY(total > 0.1 * width * height); // the layers are not all empty
        QVERIFY(icet.last().totalMs >= 0.0);
    }

    void depthTakesTheNearest() {
        const int w = 50, h = 30;
        IceTCompositor icet(comm_);
        std::vector<glm::vec4> colour(std::size_t(w) * h);
        std::vector<float> depth(colour.size());
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                const std::size_t i = std::size_t(y) * w + x;
                depth[i] = depthOf(comm_.rank(), x, y, w, h);
                colour[i] = depth[i] < 1.0f
                                ? glm::vec4(0.1f * float(comm_.rank() + 1), 0.5f, depth[i], 1.0f)
                                : glm::vec4(0.0f);
            }
        }
        std::vector<float> depthOut;
        const auto view = icet.closest(w, h, colour, depth, &depthOut);
        const std::vector<glm::vec4> out(view.begin(), view.end());
        if (comm_.rank() != 0) {
            QVERIFY(out.empty());
            return;
        }
        int mismatches = 0;
        for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
                int best = -1;
                float bestDepth = 1.0f;
                for (int r = 0; r < comm_.size(); ++r) {
                    const float d = depthOf(r, x, y, w, h);
                    if (d < bestDepth) {
                        bestDepth = d;
                        best = r;
                    }
                }
                const glm::vec4 want =
                    best < 0 ? glm::vec4(0.0f)
                             : glm::vec4(0.1f * float(best + 1), 0.5f, bestDepth, 1.0f);
                const glm::vec4 got = out[std::size_t(y) * w + x];
                if (glm::any(glm::greaterThan(glm::abs(got - want), glm::vec4(1e-6f))) ||
                    std::abs(depthOut[std::size_t(y) * w + x] - bestDepth) > 1e-6f) {
                    ++mismatches;
                }
            }
        }
        QCOMPARE(mismatches, 0);
    }

    void aBadOrderIsRefusedOnEveryRank() {
        IceTCompositor icet(comm_);
        const std::vector<glm::vec4> mine = myLayer(8, 8);
        const std::vector<int> shortOrder(std::size_t(comm_.size()) + 1, 0);
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, icet.blend(8, 8, mine, shortOrder));
        QVERIFY_THROWS_EXCEPTION(
            std::invalid_argument,
            icet.blend(9, 8, mine, std::vector<int>(std::size_t(comm_.size()))));
    }
};

LUCENT_MPI_TEST_MAIN(TestIceTCompositor)
#include "test_icet_compositor.moc"
