#pragma once

#include <memory>
#include <string>

namespace lucent {

// A current OpenGL 4.x core context without a window, made with EGL: the
// surfaceless platform on Mesa (llvmpipe here), the device platform on a
// headless NVIDIA server, the default display otherwise. The renderer draws
// into its own framebuffer objects, so no surface is needed.
class OffscreenContext {
public:
    // Creates the context and makes it current on this thread. Throws GlError
    // saying what is missing (no EGL display, no desktop GL, GL older than 4.3).
    // device >= 0: the EGL device of that index (modulo the devices there are)
    // is tried first, so that the ranks of a distributed render on a node with
    // several GPUs each take their own (by local rank).
    static std::unique_ptr<OffscreenContext> create(int device = -1);
    ~OffscreenContext();
    OffscreenContext(const OffscreenContext&) = delete;
    OffscreenContext& operator=(const OffscreenContext&) = delete;

    void makeCurrent();
    // "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6" and the like.
    std::string description() const;

private:
    struct Egl;
    explicit OffscreenContext(std::unique_ptr<Egl> egl);
    std::unique_ptr<Egl> egl_;
};

} // namespace lucent
