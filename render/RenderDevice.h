#pragma once
// The one opener of renderers: it picks GL or the CPU, makes an OpenGL context
// with EGL (or borrows the one current on this thread), and says why it fell
// back to the CPU. The CLI, the server's render thread, the 3D view and its
// quality measurement all open their renderers here.

#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "core/scene/Renderer.h"
#include "render/GpuRayCaster.h"

namespace lucent {

class OffscreenContext;

enum class RendererKind { Cpu, Gl };

// "cpu" or "gl". Throws std::invalid_argument naming the choices.
RendererKind parseRendererKind(std::string_view name);
const char* rendererKindName(RendererKind kind);

class RenderDevice {
public:
    // Gl: an OpenGL 4.3 core context made with EGL, current on this thread
    // (headless: surfaceless on Mesa, the device platform on NVIDIA). Where
    // none can be had, the CPU, and fallbackReason() says why.
    // eglDevice >= 0 prefers that EGL device (OffscreenContext::create).
    static std::unique_ptr<RenderDevice> open(RendererKind wanted, int eglDevice = -1);
    // Gl in the context current on this thread (a QOpenGLWidget's, in its
    // paint). The caller keeps that context alive and current whenever one of
    // this device's renderers renders or is destroyed.
    static std::unique_ptr<RenderDevice> borrowCurrentContext();
    ~RenderDevice();
    RenderDevice(const RenderDevice&) = delete;
    RenderDevice& operator=(const RenderDevice&) = delete;

    // What renders: Gl, or Cpu (asked for, or fallen back to).
    RendererKind kind() const { return kind_; }
    // Why GL was asked for and the CPU renders; empty otherwise.
    const std::string& fallbackReason() const { return fallbackReason_; }
    // "gl: llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6" or "cpu".
    std::string description() const;

    struct Opened {
        std::unique_ptr<Renderer> renderer;
        std::string fallbackReason; // GL failed for this volume, so the CPU renders it
    };
    // A renderer of `volume`, which must outlive it. Renderers of a device with
    // its own context keep that context and make it current when they work, so
    // they may outlive the device.
    Opened openRenderer(const Volume& volume, const GpuOptions& options = {}) const;
    // A renderer of one part of a volume (a rank of a distributed render:
    // core/volume/VolumePart.h); `part` must outlive it.
    Opened openPartRenderer(const Volume& part, const VolumePart& where,
                            const GpuOptions& options = {}) const;

private:
    Opened openWith(const std::function<std::unique_ptr<GpuRayCaster>()>& gpu,
                    const std::function<std::unique_ptr<Renderer>()>& cpu) const;
    RenderDevice(RendererKind kind, std::shared_ptr<OffscreenContext> context,
                 std::string fallbackReason);

    RendererKind kind_;
    std::shared_ptr<OffscreenContext> context_; // own context; null for the CPU or a borrowed one
    std::string fallbackReason_;
};

} // namespace lucent
