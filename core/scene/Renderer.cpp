#include "core/scene/Renderer.h"

#include <stdexcept>

namespace lucent {

RenderStats Renderer::drawInPlace(const RenderDescription&, const FramebufferTarget&) {
    throw std::logic_error("the " + backend() + " renderer cannot draw into a framebuffer");
}

} // namespace lucent
