#pragma once
// A screenshot against a baseline PNG committed under tests/ui/baselines/, with
// explicit bounds (PSNR and SSIM over RGBA). LUCENT_UPDATE_BASELINES=1 writes the
// baseline instead (look at it before committing it). On a mismatch the actual
// image is saved beside the test binaries and its path is in the message.

#include <QDir>
#include <QFileInfo>
#include <QImage>
#include <QString>

#include <algorithm>

#include "core/image/ImageMetrics.h"

namespace lucent::test {

inline const QString kBaselineDir = QStringLiteral(LUCENT_SOURCE_DIR "/tests/ui/baselines");

inline ImageRGBA8 toRgba(const QImage& image) {
    const QImage rgba = image.convertToFormat(QImage::Format_RGBA8888);
    ImageRGBA8 out = ImageRGBA8::filled(rgba.width(), rgba.height(), 0);
    for (int y = 0; y < rgba.height(); ++y) {
        const uchar* row = rgba.constScanLine(y);
        std::copy(row, row + std::size_t(rgba.width()) * 4,
                  out.pixels.begin() + std::ptrdiff_t(out.offset(0, y)));
    }
    return out;
}

struct BaselineResult {
    bool written = false; // LUCENT_UPDATE_BASELINES: the baseline was (re)written
    QString failure;      // empty when the image matches
};

// Compares `actual` with kBaselineDir/name.png; on failure saves name_actual.png
// in LUCENT_BIN_DIR.
inline BaselineResult compareWithBaseline(const QImage& actual, const QString& name, double minPsnr,
                                          double minSsim) {
    const QString baselinePath = kBaselineDir + QStringLiteral("/%1.png").arg(name);
    if (qEnvironmentVariableIsSet("LUCENT_UPDATE_BASELINES")) {
        QDir().mkpath(kBaselineDir);
        if (!actual.save(baselinePath)) {
            return {false, QStringLiteral("cannot write ") + baselinePath};
        }
        return {true, {}};
    }
    const QImage baseline(baselinePath);
    if (baseline.isNull()) {
        return {false, QStringLiteral("no baseline ") + baselinePath};
    }
    const QString saved = QStringLiteral(LUCENT_BIN_DIR "/%1_actual.png").arg(name);
    if (actual.size() != baseline.size()) {
        actual.save(saved);
        return {false, QStringLiteral("%1x%2, baseline %3x%4; actual saved as %5")
                           .arg(actual.width())
                           .arg(actual.height())
                           .arg(baseline.width())
                           .arg(baseline.height())
                           .arg(saved)};
    }
    const ImageRGBA8 a = toRgba(actual), b = toRgba(baseline);
    const double p = psnr(a, b), s = ssim(a, b);
    qInfo("%s against the baseline: PSNR %.2f dB, SSIM %.4f", qPrintable(name), p, s);
    if (p < minPsnr || s < minSsim) {
        actual.save(saved);
        return {false, QStringLiteral("PSNR %1 dB (at least %2), SSIM %3 (at least %4); actual "
                                      "saved as %5")
                           .arg(p)
                           .arg(minPsnr)
                           .arg(s)
                           .arg(minSsim)
                           .arg(saved)};
    }
    return {};
}

} // namespace lucent::test

// In a Qt Test slot: skips after writing a baseline, fails on a mismatch.
#define LUCENT_COMPARE_BASELINE(image, name, minPsnr, minSsim)                                     \
    do {                                                                                           \
        const lucent::test::BaselineResult result_ =                                               \
            lucent::test::compareWithBaseline((image), (name), (minPsnr), (minSsim));              \
        QVERIFY2(result_.failure.isEmpty(), qPrintable(result_.failure));                          \
        if (result_.written) {                                                                     \
            QSKIP(qPrintable(QStringLiteral("baseline written: ") + (name)));                      \
        }                                                                                          \
    } while (false)
