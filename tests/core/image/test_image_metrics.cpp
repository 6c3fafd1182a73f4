// PSNR and SSIM: the closed-form cases, the properties SSIM must have, and a
// comparison against a direct, unoptimised SSIM written here from the paper.
#include <QTest>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "core/image/ImageMetrics.h"

using namespace lucent;

namespace {

ImageRGBA8 randomImage(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> d(0, 255);
    ImageRGBA8 image = ImageRGBA8::filled(w, h);
    for (auto& p : image.pixels) {
        p = static_cast<std::uint8_t>(d(rng));
    }
    return image;
}

// A smooth picture (gradients and a disc), more like a rendering than noise.
ImageRGBA8 smoothImage(int w, int h) {
    ImageRGBA8 image = ImageRGBA8::filled(w, h, 255);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            const double r = std::hypot(x - w / 2.0, y - h / 2.0);
            image.at(x, y, 0) = static_cast<std::uint8_t>(255 * x / std::max(1, w - 1));
            image.at(x, y, 1) = static_cast<std::uint8_t>(255 * y / std::max(1, h - 1));
            image.at(x, y, 2) = r < w / 4.0 ? 220 : 30;
        }
    }
    return image;
}

ImageRGBA8 addNoise(const ImageRGBA8& in, double sigma, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> n(0.0, sigma);
    ImageRGBA8 out = in;
    for (std::size_t i = 0; i < out.pixels.size(); ++i) {
        if (i % 4 != 3) {
            out.pixels[i] =
                static_cast<std::uint8_t>(std::clamp(out.pixels[i] + n(rng), 0.0, 255.0));
        }
    }
    return out;
}

// SSIM straight from Wang et al. 2004, eq. (13)-(15): the 2-D window built
// directly, two-pass weighted variance and covariance, every valid position.
double referenceSsim(const ImageRGBA8& a, const ImageRGBA8& b) {
    const auto luma = [](const ImageRGBA8& im, int x, int y) {
        return 0.299 * im.at(x, y, 0) + 0.587 * im.at(x, y, 1) + 0.114 * im.at(x, y, 2);
    };
    double w[11][11];
    double wsum = 0.0;
    for (int j = 0; j < 11; ++j) {
        for (int i = 0; i < 11; ++i) {
            w[j][i] = std::exp(-((i - 5) * (i - 5) + (j - 5) * (j - 5)) / (2.0 * 1.5 * 1.5));
            wsum += w[j][i];
        }
    }
    const double c1 = std::pow(0.01 * 255, 2);
    const double c2 = std::pow(0.03 * 255, 2);
    double total = 0.0;
    int n = 0;
    for (int y0 = 0; y0 + 11 <= a.height; ++y0) {
        for (int x0 = 0; x0 + 11 <= a.width; ++x0) {
            double mx = 0, my = 0;
            for (int j = 0; j < 11; ++j) {
                for (int i = 0; i < 11; ++i) {
                    mx += w[j][i] / wsum * luma(a, x0 + i, y0 + j);
                    my += w[j][i] / wsum * luma(b, x0 + i, y0 + j);
                }
            }
            double vx = 0, vy = 0, cxy = 0;
            for (int j = 0; j < 11; ++j) {
                for (int i = 0; i < 11; ++i) {
                    const double dx = luma(a, x0 + i, y0 + j) - mx;
                    const double dy = luma(b, x0 + i, y0 + j) - my;
                    vx += w[j][i] / wsum * dx * dx;
                    vy += w[j][i] / wsum * dy * dy;
                    cxy += w[j][i] / wsum * dx * dy;
                }
            }
            total +=
                (2 * mx * my + c1) * (2 * cxy + c2) / ((mx * mx + my * my + c1) * (vx + vy + c2));
            ++n;
        }
    }
    return total / n;
}

template <class F> QString thrownMessage(F&& f) {
    try {
        f();
    } catch (const std::invalid_argument& e) {
        return QString::fromUtf8(e.what());
    }
    return {};
}

} // namespace

class TestImageMetrics : public QObject {
    Q_OBJECT
private slots:
    void psnrOfIdenticalImagesIsInfinite() {
        const ImageRGBA8 a = randomImage(20, 13, 1);
        ImageRGBA8 b = a;
        QVERIFY(std::isinf(psnr(a, b)) && psnr(a, b) > 0);
        for (std::size_t i = 3; i < b.pixels.size(); i += 4) {
            b.pixels[i] = static_cast<std::uint8_t>(255 - b.pixels[i]); // alpha is ignored
        }
        QVERIFY(std::isinf(psnr(a, b)));
    }

    void psnrOfAKnownMse() {
        const ImageRGBA8 a = ImageRGBA8::filled(16, 16, 100);
        const ImageRGBA8 b = ImageRGBA8::filled(16, 16, 110); // MSE 100
        QCOMPARE(psnr(a, b), 10.0 * std::log10(255.0 * 255.0 / 100.0));
        ImageRGBA8 c = a;
        for (int y = 0; y < c.height; ++y) {
            for (int x = 0; x < c.width; ++x) {
                c.at(x, y, 0) = 103; // only red differs: MSE = 9 / 3
            }
        }
        QCOMPARE(psnr(a, c), 10.0 * std::log10(255.0 * 255.0 / 3.0));
        // One pixel, one channel, off by 255 in a 10x10 image: MSE = 255^2 / 300.
        ImageRGBA8 d = ImageRGBA8::filled(10, 10, 0);
        ImageRGBA8 e = d;
        e.at(4, 7, 2) = 255;
        QVERIFY(std::abs(psnr(d, e) - 10.0 * std::log10(300.0)) < 1e-12);
        QCOMPARE(psnr(d, e), psnr(e, d));
    }

    void sizeMismatchNamesBothSizes() {
        const ImageRGBA8 a = ImageRGBA8::filled(16, 12);
        const ImageRGBA8 b = ImageRGBA8::filled(12, 16);
        for (const QString& m :
             {thrownMessage([&] { psnr(a, b); }), thrownMessage([&] { ssim(a, b); })}) {
            QVERIFY2(m.contains("16x12") && m.contains("12x16"), qPrintable(m));
        }
        ImageRGBA8 broken = ImageRGBA8::filled(16, 12);
        broken.pixels.pop_back();
        QVERIFY(!thrownMessage([&] { psnr(a, broken); }).isEmpty());
        QVERIFY(!thrownMessage([&] { psnr(ImageRGBA8{}, ImageRGBA8{}); }).isEmpty());
        const ImageRGBA8 tiny = ImageRGBA8::filled(10, 40);
        QVERIFY(thrownMessage([&] { ssim(tiny, tiny); }).contains("11x11"));
        QVERIFY_THROWS_EXCEPTION(std::invalid_argument, ImageRGBA8::filled(-1, 3));
    }

    void ssimOfIdenticalImagesIsOne() {
        const ImageRGBA8 a = randomImage(40, 31, 2);
        QCOMPARE(ssim(a, a), 1.0);
        const ImageRGBA8 s = smoothImage(11, 11); // a single window position
        QCOMPARE(ssim(s, s), 1.0);
        const ImageRGBA8 flat = ImageRGBA8::filled(30, 30, 0);
        QCOMPARE(ssim(flat, flat), 1.0);
    }

    void offsetAndNoiseLowerSsim() {
        const ImageRGBA8 a = smoothImage(64, 48);
        ImageRGBA8 offset = a;
        for (std::size_t i = 0; i < offset.pixels.size(); ++i) {
            if (i % 4 != 3) {
                offset.pixels[i] = static_cast<std::uint8_t>(std::min(255, offset.pixels[i] + 40));
            }
        }
        const double sOffset = ssim(a, offset);
        QVERIFY2(sOffset < 0.999 && sOffset > 0.5, qPrintable(QString::number(sOffset)));
        const double sLittle = ssim(a, addNoise(a, 5.0, 3));
        const double sMuch = ssim(a, addNoise(a, 40.0, 3));
        QVERIFY2(sLittle < 1.0 && sMuch < sLittle && sMuch > -1.0,
                 qPrintable(QString("%1 %2").arg(sLittle).arg(sMuch)));
        QVERIFY(psnr(a, addNoise(a, 40.0, 3)) < psnr(a, addNoise(a, 5.0, 3)));
    }

    void ssimIsSymmetric() {
        const ImageRGBA8 a = smoothImage(33, 27);
        const ImageRGBA8 b = addNoise(a, 20.0, 4);
        QVERIFY(std::abs(ssim(a, b) - ssim(b, a)) < 1e-14);
    }

    void ssimMatchesADirectImplementation() {
        for (const auto& [w, h] : {std::pair{16, 16}, std::pair{23, 17}, std::pair{11, 30}}) {
            const ImageRGBA8 a = randomImage(w, h, 5);
            const ImageRGBA8 b = addNoise(a, 30.0, 6);
            const ImageRGBA8 c = randomImage(w, h, 7);
            for (const ImageRGBA8* other : {&b, &c}) {
                const double got = ssim(a, *other);
                const double want = referenceSsim(a, *other);
                QVERIFY2(std::abs(got - want) < 1e-10,
                         qPrintable(QString("%1x%2: %3 vs %4").arg(w).arg(h).arg(got).arg(want)));
            }
        }
    }

    void ssimIgnoresAlphaAndUsesLuminance() {
        const ImageRGBA8 a = smoothImage(20, 20);
        ImageRGBA8 b = a;
        for (std::size_t i = 3; i < b.pixels.size(); i += 4) {
            b.pixels[i] = 0;
        }
        QCOMPARE(ssim(a, b), 1.0);
        // Swapping red and blue changes luminance: SSIM drops, PSNR is finite.
        ImageRGBA8 swapped = a;
        for (std::size_t i = 0; i < swapped.pixels.size(); i += 4) {
            std::swap(swapped.pixels[i], swapped.pixels[i + 2]);
        }
        QVERIFY(ssim(a, swapped) < 1.0);
    }
};

QTEST_APPLESS_MAIN(TestImageMetrics)
#include "test_image_metrics.moc"
