#pragma once
// The ray caster's framebuffer: premultiplied colour in 32-bit floats, the
// number of samples each ray took and the projections' values (RG32F, what
// a part of a distributed render composites from). Private to render/.

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "render/GlObjects_p.h"

namespace lucent {

class RenderTarget {
public:
    // Reallocates when the size changes.
    void resize(int width, int height);
    // Binds it for drawing and clears it. countRows: also clears the per-row
    // sample counts and binds them to image unit 0 (the ray caster's
    // uRowSamples), for countedSamples().
    void bindAndClear(bool countRows);
    // Row 0 of `colour` is the image's top row (GL's is the bottom one).
    // `projection`, when given, receives the projections' values likewise.
    void read(std::vector<glm::vec4>& colour, std::size_t& samples,
              std::vector<glm::vec2>* projection = nullptr);
    // The samples of the last frame drawn after bindAndClear(true): one value a
    // row read back (4 bytes a row), not the whole count texture.
    std::size_t countedSamples() const;

    // The premultiplied colour (RGBA32F), row 0 at the bottom.
    GLuint colour() const { return colour_.get(); }
    // A framebuffer of the target's size with one RGBA8 texture (linear
    // filtering, clamped to its edges): the frame as shown, before it is
    // stretched. Made on first use.
    GLuint shownFramebuffer();
    GLuint shown() const { return shown_.get(); }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    int width_ = 0, height_ = 0;
    GlFramebuffer framebuffer_, shownFramebuffer_;
    GlTexture colour_, samples_, projection_, rowSamples_, shown_;
    // Where read() has the driver copy the frame (a pixel pack buffer: the
    // driver's fast path), grown as needed and kept between frames.
    GlBuffer readBuffer_;
    std::size_t readBufferBytes_ = 0;
};

} // namespace lucent
