#pragma once
// The ray caster's framebuffer: premultiplied colour in 32-bit floats and the
// number of samples each ray took. Private to render/.

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "render/GlObjects_p.h"

namespace lucent {

class RenderTarget {
public:
    // Reallocates when the size changes.
    void resize(int width, int height);
    void bindAndClear();
    // Row 0 of `colour` is the image's top row (GL's is the bottom one).
    void read(std::vector<glm::vec4>& colour, std::size_t& samples) const;

private:
    int width_ = 0, height_ = 0;
    GlFramebuffer framebuffer_;
    GlTexture colour_, samples_;
};

} // namespace lucent
