#include "render/GpuBudget.h"

#include <epoxy/gl.h>

namespace lucent {

GpuBudget gpuBudget(std::size_t asked) {
    if (asked > 0) {
        return {asked, "asked for"};
    }
    GLint kib[4] = {0, 0, 0, 0};
    if (epoxy_has_gl_extension("GL_NVX_gpu_memory_info")) {
        glGetIntegerv(GL_GPU_MEMORY_INFO_TOTAL_AVAILABLE_MEMORY_NVX, kib);
        if (kib[0] > 0) {
            return {std::size_t(kib[0]) * 1024 / 2,
                    "half of the " + std::to_string(kib[0] / 1024) + " MiB the GPU reports"};
        }
    }
    if (epoxy_has_gl_extension("GL_ATI_meminfo")) {
        glGetIntegerv(GL_TEXTURE_FREE_MEMORY_ATI, kib);
        if (kib[0] > 0) {
            return {std::size_t(kib[0]) * 1024 / 2, "half of the " + std::to_string(kib[0] / 1024) +
                                                        " MiB of free texture memory reported"};
        }
    }
    while (glGetError() != GL_NO_ERROR) {
    }
    return {std::size_t(1) << 30, "1 GiB: the driver reports no memory size"};
}

} // namespace lucent
