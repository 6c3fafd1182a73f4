#pragma once
// What the GL suites share: the context, the real CT, and image comparison
// that saves both images when a bound fails.

#include <QTest>

#include <filesystem>
#include <memory>
#include <string>

#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"
#include "render/GpuRayCaster.h"
#include "render/OffscreenContext.h"

namespace lucent::test {

inline std::filesystem::path philipsCt() {
    return std::filesystem::path(LUCENT_TEST_DATA_DIR) / "dcm_qa_ct/Philips_S21570/S2020";
}

// PSNR of the GPU image against the reference; below `bound` both images are
// written next to the test binary (gl_failed_<name>_{gpu,cpu}.png) and the
// caller's QVERIFY fails with the figures.
inline double comparedPsnr(const ImageRGBA8& gpu, const ImageRGBA8& reference,
                           const std::string& name, double bound) {
    const double p = psnr(gpu, reference);
    if (p < bound) {
        const std::filesystem::path dir = std::filesystem::path(LUCENT_BIN_DIR);
        writePng(gpu, dir / ("gl_failed_" + name + "_gpu.png"));
        writePng(reference, dir / ("gl_failed_" + name + "_cpu.png"));
        qWarning("%s: psnr %.2f dB < %.1f dB; images saved as %s/gl_failed_%s_*.png", name.c_str(),
                 p, bound, dir.c_str(), name.c_str());
    }
    return p;
}

} // namespace lucent::test
