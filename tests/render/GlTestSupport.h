#pragma once
// What the GL suites share: the context, the real CT, image comparison that
// saves both images when a bound fails, and a framebuffer like a widget's.

#include <QTest>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>

#include "core/image/ImageMetrics.h"
#include "core/image/PngIO.h"
#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"
#include "render/GlError.h"
#include "render/GlObjects_p.h"
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

// An RGBA8 framebuffer like a QOpenGLWidget's, in the current context.
class TestFramebuffer {
public:
    TestFramebuffer(int width, int height) : width_(width), height_(height) {
        texture_ = makeTexture2D(GL_RGBA8, width, height);
        framebuffer_ = makeFramebuffer({{GL_COLOR_ATTACHMENT0, texture_.get()}}, "test");
        const GLfloat magenta[4] = {1, 0, 1, 1}; // every pixel a test reads must be drawn over
        glClearNamedFramebufferfv(framebuffer_.get(), GL_COLOR, 0, magenta);
    }
    GLuint name() const { return framebuffer_.get(); }
    FramebufferTarget whole() const { return {name(), 0, 0, width_, height_}; }
    void clear(const glm::vec4& colour) {
        glClearNamedFramebufferfv(name(), GL_COLOR, 0, &colour[0]);
    }
    // The rectangle (GL's origin: bottom left) as an image, top row first.
    ImageRGBA8 read(int x, int y, int width, int height) const {
        ImageRGBA8 bottomUp = ImageRGBA8::filled(width, height);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glGetTextureSubImage(texture_.get(), 0, x, y, 0, width, height, 1, GL_RGBA,
                             GL_UNSIGNED_BYTE, GLsizei(bottomUp.pixels.size()),
                             bottomUp.pixels.data());
        checkGl("reading the test framebuffer");
        ImageRGBA8 image = ImageRGBA8::filled(width, height);
        for (int row = 0; row < height; ++row) {
            std::copy_n(bottomUp.at(0, height - 1 - row), 4 * width, image.at(0, row));
        }
        return image;
    }
    ImageRGBA8 read() const { return read(0, 0, width_, height_); }

private:
    int width_, height_;
    GlTexture texture_;
    GlFramebuffer framebuffer_;
};

} // namespace lucent::test
