#pragma once

#include <memory>
#include <optional>

#include "render/RenderBackend.h"
#include "render/RenderDevice.h"

namespace lucent {

// The ray casters of this computer behind RenderBackend, opened through
// RenderDevice: the GPU ray caster in the caller's OpenGL context
// (RendererKind::Gl: RenderDevice::borrowCurrentContext()), or the CPU ray
// caster. They render in the caller's thread: request() only records the
// newest description and emits renderWanted(), and the caller (the 3D view's
// surface, from its paint) calls drawPending() (GL: the frame drawn straight
// into its framebuffer) or renderPending() (an image), which emit frameReady()
// before they return.
class LocalRenderBackend : public RenderBackend {
    Q_OBJECT

public:
    explicit LocalRenderBackend(QObject* parent = nullptr);
    // A GL renderer must have been released (releaseGl) with its context current.
    ~LocalRenderBackend() override;

    // Gl renders in the context current when drawPending() or renderPending()
    // is called, the same one on every call until releaseGl(). Leaving Gl
    // needs releaseGl() first (std::logic_error otherwise).
    void setKind(RendererKind kind);
    RendererKind kind() const { return kind_; }
    void setGpuOptions(const GpuOptions& options) { gpuOptions_ = options; }

    void setVolume(std::shared_ptr<const Volume> volume) override;
    // The surface shown with the volume (null: none), drawn by the GL
    // renderer only (GpuRayCaster::setSurface): kept, and given to every
    // renderer opened later. A frame drawn in place is drawn again with it
    // (renderWanted()). Throws std::invalid_argument for a display
    // checkSurfaceDisplay() refuses (render/SurfaceRenderer.h), whatever the kind.
    void setSurface(std::shared_ptr<const SurfaceDisplay> surface);
    // Whether the frames show the surface: one is set and the renderer draws
    // surfaces (GL does, the CPU does not); before a renderer is opened,
    // whether the kind is Gl. What the view tells the user.
    bool surfaceShown() const;
    void request(const RenderDescription& still, const FrameOptions& options) override;
    bool pending() const { return pending_.has_value(); }

    // Renders the newest request, if there is one, and emits its frame with the
    // image (read back from the GPU with Gl). A bad setting emits
    // frameFailed(). When OpenGL fails (GlError, or BudgetError: not even the
    // coarsest level fits) the GL renderer is dropped, gpuFailed() says why
    // and the request stays pending for the next kind.
    void renderPending();
    // For a surface with a framebuffer (`target`, of the current context):
    // the newest request drawn into it with no read back (frameReady() with
    // inPlace and no image; a renderer that cannot draw in place clears it and
    // sends the image); with none, the last frame drawn in place again (no
    // new frame); else the rectangle cleared to black. Failures as
    // renderPending(); never throws.
    void drawPending(const FramebufferTarget& target);
    // The last frame as rendered (an interactive one at its smaller size),
    // read back on request (screenshots, tests): its description rendered
    // again. Empty when there is none. Gl: with the context current.
    ImageRGBA8 readLastFrame();
    // The renderer's figures of its last frame (Renderer::frameDetails); empty
    // before the first.
    FrameDetails lastFrameDetails() const;

    // Frees the GL renderer's textures and buffers: call with its context
    // current, before that context goes.
    void releaseGl();
    bool holdsGlResources() const { return renderer_ != nullptr && rendererIsGl_; }

signals:
    // A request is waiting: call drawPending() or renderPending() soon (from the paint).
    void renderWanted();
    void gpuFailed(const QString& reason);

private:
    struct Pending {
        RenderDescription still;
        FrameOptions options;
    };
    // The renderer of the current volume and kind, opened on first use.
    // Throws GlError where GL was wanted and the renderer fell back to the CPU.
    Renderer& renderer();
    void dropRenderer();
    // Renders or draws the pending request; false when it failed (signals sent).
    bool renderJob(const FramebufferTarget* target);
    // The last frame drawn in place, drawn again; false when there is none.
    bool drawLast(const FramebufferTarget& target);

    RendererKind kind_ = RendererKind::Cpu;
    // The workstation's: a frame uploads at most this beyond what it must
    // show; the finer bricks stream in over the next frames (kept asking for
    // while a frame says some are pending), so that a move never waits on
    // a whole volume's upload.
    static constexpr std::size_t kStreamBytesPerFrame = std::size_t(64) << 20;
    GpuOptions gpuOptions_ = [] {
        GpuOptions o;
        o.uploadBytesPerFrame = kStreamBytesPerFrame;
        return o;
    }();
    std::shared_ptr<const Volume> volume_;
    std::optional<Pending> pending_;
    // The renderer and the volume it renders, kept alive as long as it is.
    std::shared_ptr<const Volume> rendererVolume_;
    std::unique_ptr<Renderer> renderer_;
    bool rendererIsGl_ = false;
    std::shared_ptr<const SurfaceDisplay> surface_;
    bool rendererDrawsSurfaces_ = false; // what the renderer's setSurface() answered
    // The description of the renderer's last frame, and whether it was drawn in place.
    std::optional<RenderDescription> last_;
    bool lastInPlace_ = false;
};

} // namespace lucent
