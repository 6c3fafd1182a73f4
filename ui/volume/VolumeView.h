#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>

#include <QImage>
#include <QPointF>
#include <QString>
#include <QSurfaceFormat>
#include <QWidget>

#include "core/quality/InteractiveQuality.h"
#include "core/raycast/CpuRayCaster.h"
#include "core/scene/RenderDescription.h"
#include "core/scene/SurfaceDisplay.h"
#include "render/LocalRenderBackend.h"
#include "render/RemoteRenderBackend.h"
#include "ui/volume/ClipBoxHandles.h"
#include "ui/volume/OrientationCube.h"

class QPainter;

namespace lucent {

class RotatingMip;

// The 3D view: the volume ray cast on the GPU (GpuRayCaster in a QOpenGLWidget's
// context, each frame drawn straight into the widget's framebuffer) or, where
// OpenGL 4.3 cannot be had, on the CPU (CpuRayCaster), with a one-line notice
// saying why; or on a lucent-server (renderOnServer), switched at run time. Frames come from a
// RenderBackend (LocalRenderBackend or RemoteRenderBackend); the view owns the camera, mode, clip
// box and transfer function it renders with, so a switch keeps them.
//
// Mouse: left-drag rotates (kDegreesPerPixel of azimuth per pixel right, of
// elevation per pixel down), right-drag zooms (up = closer), middle-drag pans
// the camera (what lies at the point looked at follows the mouse), the wheel
// zooms (kWheelZoomPerNotch per notch), Shift+wheel moves the eye towards the
// point looked at (kDollyPerNotch of its distance per notch; on into the
// volume). B shows the clip box with a handle on each face: a left-drag on a
// handle moves that face. While a button is down frames use
// interactiveDescription() scaled up to the view; on release one frame at full
// quality follows. Ctrl+Shift+R: the rotating MIP (rotatingMip()). A PET series opens in
// MIP, inverted grey on white (core/pet/PetProjection.h).
class VolumeView : public QWidget {
    Q_OBJECT

public:
    enum class Backend { Gpu, Cpu, Remote };
    static constexpr double kDegreesPerPixel = 0.5;
    static constexpr double kZoomPerPixel = 0.01; // zoom *= exp(-dy * this)
    static constexpr double kWheelZoomPerNotch = 1.1;
    static constexpr double kDollyPerNotch = 0.85; // distance *= this per notch forward
    static constexpr double kHandleRadius = 8.0;   // pixels

    // preferred = Gpu tries OpenGL first and falls back to the CPU by itself.
    explicit VolumeView(QWidget* parent = nullptr, Backend preferred = Backend::Gpu);
    ~VolumeView() override;

    // The format the GL path asks for (4.3 core). Best set as the application's
    // default with QSurfaceFormat::setDefaultFormat before QApplication exists.
    static QSurfaceFormat surfaceFormat();

    void setVolume(std::shared_ptr<const Volume> volume);
    const std::shared_ptr<const Volume>& volume() const { return volume_; }
    std::uint64_t volumeGeneration() const { return volumeGeneration_; }

    const TransferFunction& transferFunction() const { return transferFunction_; }
    const Camera& camera() const { return camera_; }
    RenderMode mode() const { return mode_; }
    // The rotating MIP (its action goes into menus and the controls).
    RotatingMip* rotatingMip() const { return rotatingMip_; }
    double isoValue() const { return isoValue_; }
    const ClipBox& clipBox() const { return clip_; }
    const SamplingSettings& sampling() const { return sampling_; }
    // The clip box's face handles where they are on the view now.
    bool clipHandlesShown() const { return clipHandlesShown_; }
    ClipHandles clipHandles() const;
    void setInteractiveQuality(const InteractiveQuality& quality) { quality_ = quality; }
    // The orientation cube in the bottom-left corner (shown by default), turned
    // by the camera; where it is on the view now (VolumeViewMarker.cpp).
    bool orientationMarkerShown() const { return orientationMarkerShown_; }
    void setOrientationMarkerShown(bool shown);
    OrientationCube orientationMarker() const;

    // What a still frame renders now, at this size in device pixels (the view's
    // size when not given).
    RenderDescription description() const;
    RenderDescription description(int width, int height) const;

    Backend backend() const { return backend_; }
    // Renders on a lucent-server from now on: camera, transfer function, mode
    // and clip box go with it. The connection status is in notice().
    void renderOnServer(const RemoteServerSettings& settings);
    // Back to this computer: the GPU, or the CPU where OpenGL cannot be had.
    void renderLocally();
    // Follows a teaching session on a server (VolumeViewFollow.cpp): its frames,
    // pointer and marks, no volume needed here. A drag looks around (free look,
    // from the session's camera); remoteBackend().backToTeacher() ends it.
    // renderLocally() or renderOnServer() stop following.
    void followSession(const SessionFollow& follow);
    bool followsSession() const;
    LocalRenderBackend& localBackend() { return *local_; }
    RemoteRenderBackend& remoteBackend() { return *remote_; }

    // The view's notice line: why it is not on the GPU, the server's status, or
    // the last render error; empty otherwise.
    QString notice() const { return notice_; }
    bool interacting() const { return dragButton_ != Qt::NoButton; }
    // The last frame as shown (scaled up when it was an interactive one). A
    // frame the GPU drew in place is read back here, on the first call after
    // it (rendered again: for screenshots and tests, not for every frame).
    const ImageRGBA8& lastFrame();
    // Whether it shows the newest request (a server's frames may lag behind).
    bool lastFrameCurrent() const { return lastFrameCurrent_; }
    // The view's pixels as on screen.
    QImage grabImage();

    // Used by the surfaces, from their paint. The frame surface renders a
    // waiting local request and paints the frame and the overlays; the GL
    // surface draws the request (or the last frame again) in place into its
    // framebuffer, its context current, and paints the overlays over it.
    void renderPending();
    void drawFrameInPlace(const FramebufferTarget& target);
    void paintFrame(QPainter& painter);
    // Called when OpenGL fails: switches to the CPU renderer.
    void fallBackToCpu(const QString& reason);

public slots:
    void setTransferFunction(const lucent::TransferFunction& tf);
    void setCamera(const lucent::Camera& camera);
    void resetCamera();
    void setMode(lucent::RenderMode mode);
    void setIsoValue(double value);
    void setClipBox(const lucent::ClipBox& clip);
    void setSampling(const lucent::SamplingSettings& sampling);
    void setClipHandlesShown(bool shown);
    void requestRender();

public:
    // A surface shown with the volume (null: none), with the radius of its
    // SVR field for the colour bar. The GPU renderer draws it; on the CPU or
    // a server the notice says it is not shown.
    void setSurfaceDisplay(std::shared_ptr<const SurfaceDisplay> display, double radiusMm);
    const std::shared_ptr<const SurfaceDisplay>& surfaceDisplay() const { return surfaceDisplay_; }

    // A second series already on this volume's grid (core/fusion resampleOverlay), drawn
    // along the same rays in `style`'s colour map (null: none). Left out in isosurface mode
    // and on a render server, which draw the base alone.
    // `unit` labels its colour bar ("HU", "SUVbw").
    void setOverlay(std::shared_ptr<const Volume> onGrid, const FusionStyle& style,
                    const QString& unit = {});
    void setOverlayStyle(const FusionStyle& style);
    const std::shared_ptr<const Volume>& overlay() const { return overlay_; }

signals:
    void volumeChanged();
    void cameraChanged(const lucent::Camera& camera);
    void modeChanged(lucent::RenderMode mode);
    void transferFunctionChanged(const lucent::TransferFunction& tf);
    // After each frame: its statistics and whether it was an interactive one.
    void renderedFrame(const lucent::RenderStats& stats, bool interactive);
    void noticeChanged(const QString& notice);
    void backendChanged(lucent::VolumeView::Backend backend);
    void clipBoxChanged(const lucent::ClipBox& clip);
    void clipHandlesShownChanged(bool shown);

protected:
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    void resizeEvent(QResizeEvent* event) override;

private:
    void useSurface(Backend backend);
    void connectFollowing(); // from the constructor
    // A drag while following a session: looks around first.
    void lookAroundOnDrag();
    RenderBackend& activeBackend();
    void onFrame(const BackendFrame& frame);
    void onFrameFailed(const QString& reason);
    void updateNotice();
    void updateSurface();
    void paintClipBox(QPainter& painter) const;
    void paintOrientationMarker(QPainter& painter) const;
    // Millimetres at the point looked at per view pixel.
    double mmPerPixel(const Camera& camera) const;

    std::shared_ptr<const Volume> volume_;
    std::uint64_t volumeGeneration_ = 0;
    // Before surface_: the GL surface releases the local backend's GL resources
    // when it goes, so the backends must outlive it.
    std::unique_ptr<LocalRenderBackend> local_;
    std::unique_ptr<RemoteRenderBackend> remote_;

    TransferFunction transferFunction_;
    Camera camera_;
    RenderMode mode_ = RenderMode::Dvr;
    double isoValue_ = 300.0;
    ClipBox clip_;
    SamplingSettings sampling_;
    InteractiveQuality quality_;
    bool clipHandlesShown_ = false;
    bool orientationMarkerShown_ = true;

    std::shared_ptr<const SurfaceDisplay> surfaceDisplay_;
    std::shared_ptr<const Volume> overlay_; // on volume_'s grid
    FusionStyle overlayStyle_;
    QString overlayUnit_;
    double surfaceRadius_ = 0.0;

    Backend backend_ = Backend::Cpu;
    std::unique_ptr<QWidget> surface_; // a child: VolumeGlSurface or VolumeFrameSurface
    QString notice_;
    QString backendNotice_; // why not the GPU, or the server's status
    QString frameError_;    // the last request that failed, until a frame comes
    QString detailNotice_;  // a still frame at a coarser level, or bricks still streaming in
    QString glFailure_;
    ImageRGBA8 lastFrame_; // empty for a frame drawn in place until it is read back
    std::optional<std::array<double, 12>> lastProjection_; // a server's: where its marks lie
    bool lastFrameCurrent_ = false;
    bool frameInPlace_ = false; // the GL surface's framebuffer holds the last frame
    QSize frameSize_;           // the view's size in pixels when it came

    RotatingMip* rotatingMip_; // a child

    Qt::MouseButton dragButton_ = Qt::NoButton;
    QPointF dragStart_;
    Camera dragCamera_;
    std::optional<int> dragHandle_; // the clip face being dragged
    ClipBox dragClip_;
};

} // namespace lucent
