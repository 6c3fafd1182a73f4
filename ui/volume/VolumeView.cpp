#include "ui/volume/VolumeView.h"

#include <algorithm>
#include <cmath>

#include <QGuiApplication>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QPainter>
#include <QPen>
#include <QStackedLayout>
#include <QWheelEvent>

#include "core/pet/PetProjection.h"
#include "core/scene/ViewFrame.h"
#include "ui/fusion/FusionColourBar.h"
#include "ui/volume/RotatingMip.h"
#include "ui/volume/SurfaceColourBar.h"
#include "ui/volume/TeachingMarksOverlay.h"
#include "ui/volume/VolumeSurfaces.h"

namespace lucent {

namespace {

// Qt platforms whose windows can hold a QOpenGLWidget. Others (offscreen,
// minimal, vnc, linuxfb) may still make a GL context, offscreen through GLX
// when DISPLAY is set, but their backing store has no texture to compose the
// widget into and Qt crashes in its flush; the CPU renderer is used there.
bool platformComposesGlWidgets() {
    const QString name = QGuiApplication::platformName();
    return name == "xcb" || name.startsWith("wayland") || name.startsWith("eglfs") ||
           name == "windows" || name == "cocoa";
}

// Why a 4.3 core context cannot be made here; empty when it can.
QString glUnavailableReason() {
    if (!platformComposesGlWidgets()) {
        return QObject::tr("the '%1' Qt platform cannot show OpenGL widgets")
            .arg(QGuiApplication::platformName());
    }
    QOpenGLContext probe;
    probe.setFormat(VolumeView::surfaceFormat());
    if (!probe.create()) {
        return QObject::tr("no OpenGL context on this display");
    }
    const QSurfaceFormat f = probe.format();
    if (f.version() < qMakePair(4, 3) || f.profile() != QSurfaceFormat::CoreProfile) {
        return QObject::tr("OpenGL %1.%2 only; the GPU renderer needs 4.3 core")
            .arg(f.majorVersion())
            .arg(f.minorVersion());
    }
    return {};
}

TransferFunction defaultTransferFunction(const Volume* volume) {
    if (volume != nullptr && volume->modality == "PT" && !volume->empty()) {
        return petMipTransferFunction(*volume); // PET opens in MIP, inverted grey
    }
    const bool mr = volume != nullptr && volume->modality == "MR";
    try {
        return loadPreset(mr ? "mr-default" : "ct-bone");
    } catch (const std::exception&) {
        // No presets installed: a grey ramp over the data.
        const auto [lo, hi] = volume ? volume->valueRange() : std::pair{0.0, 1.0};
        TransferFunction tf;
        tf.name = "ramp";
        tf.opacity = {{lo, 0.0}, {hi > lo ? hi : lo + 1.0, 0.5}};
        tf.colour = {{lo, glm::dvec3(1.0)}};
        return tf;
    }
}

} // namespace

VolumeView::VolumeView(QWidget* parent, Backend preferred)
    : QWidget(parent), local_(std::make_unique<LocalRenderBackend>()),
      remote_(std::make_unique<RemoteRenderBackend>()),
      transferFunction_(defaultTransferFunction(nullptr)), rotatingMip_(new RotatingMip(this)) {
    setMinimumSize(120, 120);
    setFocusPolicy(Qt::StrongFocus);
    auto* layout = new QStackedLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    for (RenderBackend* backend :
         {static_cast<RenderBackend*>(local_.get()), static_cast<RenderBackend*>(remote_.get())}) {
        connect(backend, &RenderBackend::frameReady, this, [this, backend](const BackendFrame& f) {
            if (backend == &activeBackend()) {
                onFrame(f);
            }
        });
        connect(backend, &RenderBackend::frameFailed, this, [this, backend](const QString& why) {
            if (backend == &activeBackend()) {
                onFrameFailed(why);
            }
        });
    }
    connect(local_.get(), &LocalRenderBackend::renderWanted, this, &VolumeView::updateSurface);
    // Not now: the GL surface is in the middle of painting and is replaced.
    connect(local_.get(), &LocalRenderBackend::gpuFailed, this, &VolumeView::fallBackToCpu,
            Qt::QueuedConnection);
    connect(remote_.get(), &RemoteRenderBackend::marksChanged, this, [this] {
        if (backend_ == Backend::Remote) {
            updateSurface();
        }
    });
    connect(remote_.get(), &RemoteRenderBackend::statusChanged, this, [this] {
        if (backend_ == Backend::Remote) {
            frameError_.clear();
            updateNotice();
        }
    });
    connectFollowing();
    if (preferred == Backend::Gpu) {
        glFailure_ = glUnavailableReason();
    } else {
        glFailure_ = tr("the CPU renderer was chosen");
    }
    useSurface(glFailure_.isEmpty() ? Backend::Gpu : Backend::Cpu);
}

VolumeView::~VolumeView() {
    // The backends outlive the surface; nothing they say reaches a view going away.
    local_->disconnect(this);
    remote_->disconnect(this);
}

QSurfaceFormat VolumeView::surfaceFormat() {
    QSurfaceFormat format = QSurfaceFormat::defaultFormat();
    if (format.version() < qMakePair(4, 3) || format.profile() != QSurfaceFormat::CoreProfile) {
        format.setVersion(4, 3);
        format.setProfile(QSurfaceFormat::CoreProfile);
    }
    return format;
}

RenderBackend& VolumeView::activeBackend() {
    if (backend_ == Backend::Remote) {
        return *remote_;
    }
    return *local_;
}

void VolumeView::useSurface(Backend backend) {
    auto* layout = static_cast<QStackedLayout*>(this->layout());
    const bool wasRemote = backend_ == Backend::Remote;
    if (frameInPlace_) {
        // The next surface shows the frame until its own comes: read it back
        // while the GL surface and its context are still there.
        lastFrame();
        frameInPlace_ = false;
    }
    // A GL surface releases the local backend's GL resources as it goes.
    surface_.reset();
    backend_ = backend;
    if (backend == Backend::Gpu) {
        local_->setKind(RendererKind::Gl);
        surface_ = std::make_unique<VolumeGlSurface>(this);
    } else {
        local_->setKind(RendererKind::Cpu);
        surface_ = std::make_unique<VolumeFrameSurface>(this);
    }
    if (backend != Backend::Remote && wasRemote) {
        remote_->disconnectFromServer();
    }
    layout->addWidget(surface_.get());
    layout->setCurrentWidget(surface_.get());
    frameError_.clear();
    updateNotice();
    emit backendChanged(backend_);
    requestRender();
}

void VolumeView::renderOnServer(const RemoteServerSettings& settings) {
    remote_->setVolume(volume_);
    if (backend_ != Backend::Remote) {
        useSurface(Backend::Remote);
    }
    if (settings != remote_->settings() || remote_->followed() ||
        remote_->status() == BackendStatus::Failed ||
        remote_->status() == BackendStatus::Disconnected) {
        remote_->connectTo(settings);
    }
    requestRender();
}

void VolumeView::renderLocally() {
    if (backend_ != Backend::Remote) {
        return;
    }
    useSurface(glFailure_.isEmpty() ? Backend::Gpu : Backend::Cpu);
}

void VolumeView::fallBackToCpu(const QString& reason) {
    if (backend_ != Backend::Gpu) {
        return;
    }
    glFailure_ = reason;
    useSurface(Backend::Cpu);
}

void VolumeView::updateNotice() {
    QString line;
    if (backend_ == Backend::Cpu) {
        line = tr("3D on the CPU: %1").arg(glFailure_);
    } else if (backend_ == Backend::Remote) {
        line = tr("3D on the server: %1").arg(remote_->statusMessage());
    }
    if (surfaceDisplay_ && backend_ != Backend::Gpu) {
        line +=
            (line.isEmpty() ? "" : "; ") + tr("the surface is shown with the GPU renderer only");
    }
    if (!frameError_.isEmpty()) {
        line = line.isEmpty() ? frameError_ : line + "; " + frameError_;
    }
    if (!detailNotice_.isEmpty()) {
        line = line.isEmpty() ? detailNotice_ : line + "; " + detailNotice_;
    }
    if (line != notice_) {
        notice_ = line;
        emit noticeChanged(notice_);
        updateSurface();
    }
}

void VolumeView::updateSurface() {
    if (surface_) {
        surface_->update();
    }
}

void VolumeView::setSurfaceDisplay(std::shared_ptr<const SurfaceDisplay> display, double radiusMm) {
    surfaceDisplay_ = std::move(display);
    surfaceRadius_ = radiusMm;
    local_->setSurface(surfaceDisplay_);
    updateNotice();
    requestRender();
}

void VolumeView::setVolume(std::shared_ptr<const Volume> volume) {
    volume_ = std::move(volume);
    overlay_.reset(); // it lay on the old volume's grid
    ++volumeGeneration_;
    // The GPU caster is remade on its next frame, in its own context.
    local_->setVolume(volume_);
    remote_->setVolume(volume_);
    lastFrame_ = {};
    lastFrameCurrent_ = false;
    frameInPlace_ = false;
    transferFunction_ = defaultTransferFunction(volume_.get());
    clip_ = ClipBox{};
    camera_ = Camera{};
    if (volume_ && volume_->modality == "PT") {
        setMode(RenderMode::Mip); // the classic PET display
    }
    emit volumeChanged();
    emit transferFunctionChanged(transferFunction_);
    emit cameraChanged(camera_);
    requestRender();
}

void VolumeView::setTransferFunction(const TransferFunction& tf) {
    if (tf == transferFunction_) {
        return;
    }
    transferFunction_ = tf;
    emit transferFunctionChanged(transferFunction_);
    requestRender();
}

void VolumeView::setCamera(const Camera& camera) {
    camera_ = camera;
    emit cameraChanged(camera_);
    requestRender();
}

void VolumeView::resetCamera() {
    setCamera(Camera{});
}

void VolumeView::setMode(RenderMode mode) {
    if (mode != mode_) {
        mode_ = mode;
        emit modeChanged(mode_);
    }
    requestRender();
}

void VolumeView::setIsoValue(double value) {
    isoValue_ = value;
    requestRender();
}

void VolumeView::setClipBox(const ClipBox& clip) {
    clip_ = clip;
    emit clipBoxChanged(clip_);
    requestRender();
}

void VolumeView::setClipHandlesShown(bool shown) {
    if (shown == clipHandlesShown_) {
        return;
    }
    clipHandlesShown_ = shown;
    emit clipHandlesShownChanged(shown);
    updateSurface();
}

ClipHandles VolumeView::clipHandles() const {
    if (!volume_) {
        return {};
    }
    return lucent::clipHandles(volume_->geometry(), camera_, clip_, QSizeF(size()));
}

double VolumeView::mmPerPixel(const Camera& camera) const {
    if (!volume_) {
        return 0.0;
    }
    const int w = std::max(1, width()), h = std::max(1, height());
    const double distance =
        camera.distance > 0.0 ? camera.distance : fitDistance(volume_->geometry(), camera, w, h);
    return 2.0 * distance * std::tan(glm::radians(camera.fieldOfView) * 0.5) / camera.zoom / h;
}

void VolumeView::setSampling(const SamplingSettings& sampling) {
    sampling_ = sampling;
    requestRender();
}

void VolumeView::requestRender() {
    if (!surface_) {
        return;
    }
    if ((!volume_ || volume_->empty()) && !followsSession()) {
        updateSurface();
        return;
    }
    activeBackend().request(description(), FrameOptions{interacting(), quality_});
}

void VolumeView::resizeEvent(QResizeEvent* event) {
    QWidget::resizeEvent(event);
    requestRender();
}

RenderDescription VolumeView::description() const {
    const QSize s = size() * devicePixelRatioF();
    return description(std::max(1, s.width()), std::max(1, s.height()));
}

RenderDescription VolumeView::description(int width, int height) const {
    RenderDescription d;
    d.volume = volume_.get();
    d.transferFunction = transferFunction_;
    d.camera = camera_;
    d.mode = mode_;
    d.background = transferFunctionBackground(transferFunction_);
    d.isoValue = isoValue_;
    d.clip = clip_;
    d.sampling = sampling_;
    d.width = width;
    d.height = height;
    if (overlay_ && mode_ != RenderMode::Isosurface && backend_ != Backend::Remote) {
        d.overlay.volume = overlay_.get();
        d.overlay.style = overlayStyle_;
    }
    return d;
}

QImage VolumeView::grabImage() {
    if (auto* gl = qobject_cast<VolumeGlSurface*>(surface_.get())) {
        return gl->grabFramebuffer();
    }
    return surface_->grab().toImage();
}

void VolumeView::renderPending() {
    if (backend_ != Backend::Remote) {
        local_->renderPending();
    }
}

void VolumeView::drawFrameInPlace(const FramebufferTarget& target) {
    local_->drawPending(target);
}

const ImageRGBA8& VolumeView::lastFrame() {
    if (frameInPlace_ && lastFrame_.empty()) {
        if (auto* gl = qobject_cast<VolumeGlSurface*>(surface_.get())) {
            const ImageRGBA8 image = gl->readLastFrame();
            const bool shownAsIs = image.empty() || (image.width == frameSize_.width() &&
                                                     image.height == frameSize_.height());
            lastFrame_ =
                shownAsIs ? image : scaledTo(image, frameSize_.width(), frameSize_.height());
        }
    }
    return lastFrame_;
}

void VolumeView::onFrame(const BackendFrame& frame) {
    const RenderDescription still = description();
    frameInPlace_ = frame.inPlace;
    frameSize_ = QSize(still.width, still.height);
    if (frame.inPlace) {
        lastFrame_ = {}; // in the GL surface's framebuffer; read back on request
    } else {
        lastFrame_ =
            frame.interactive ? scaledTo(frame.image, still.width, still.height) : frame.image;
    }
    lastFrameCurrent_ = frame.current;
    lastProjection_ = frame.projection;
    // What a still frame shows, when it is not the whole volume at full resolution.
    const QString detail =
        frame.interactive || (frame.stats.lod == 0 && frame.stats.bricksPending == 0) ? QString()
        : frame.stats.bricksPending > 0
            ? tr("Streaming: %n brick(s) still at a coarser level", "",
                 int(frame.stats.bricksPending))
            : tr("Coarser level of detail: %1").arg(QString::fromStdString(frame.stats.lodReason));
    if (!frameError_.isEmpty() || detail != detailNotice_) {
        frameError_.clear();
        detailNotice_ = detail;
        updateNotice();
    }
    emit renderedFrame(frame.stats, frame.interactive);
    if (backend_ == Backend::Remote) {
        updateSurface(); // local frames come from inside the surface's paint
    }
}

void VolumeView::onFrameFailed(const QString& reason) {
    frameError_ = tr("Cannot render: %1").arg(reason);
    updateNotice();
}

void VolumeView::paintFrame(QPainter& painter) {
    const QRectF area(QPointF(0, 0), QSizeF(painter.device()->width(), painter.device()->height()));
    // A frame drawn in place is under the painter already: only the overlays go over it.
    const bool hasVolume = (volume_ && !volume_->empty()) || followsSession();
    const bool inPlace = frameInPlace_ && hasVolume;
    if (!inPlace) {
        painter.fillRect(area, Qt::black);
    }
    if (!hasVolume) {
        painter.setPen(Qt::gray);
        painter.drawText(area, Qt::AlignCenter, tr("No volume"));
    } else if (inPlace || !lastFrame_.pixels.empty()) {
        if (!inPlace) {
            const QImage image(lastFrame_.pixels.data(), lastFrame_.width, lastFrame_.height,
                               4 * lastFrame_.width, QImage::Format_RGBA8888);
            painter.setRenderHint(QPainter::SmoothPixmapTransform, false);
            painter.drawImage(area, image);
        }
        if (clipHandlesShown_ && volume_) {
            paintClipBox(painter);
        }
        // Not over a followed session's frames: the view's camera is not theirs.
        if (orientationMarkerShown_ &&
            (!followsSession() || remote_->followState() == FollowState::LookingAround)) {
            paintOrientationMarker(painter);
        }
        if (surfaceDisplay_ && local_->surfaceShown() && backend_ == Backend::Gpu) {
            paintSurfaceColourBar(painter, area, *surfaceDisplay_, surfaceRadius_);
        }
        if (overlay_ && mode_ != RenderMode::Isosurface && backend_ != Backend::Remote) {
            const int h = std::min(int(area.height()) / 2, 240);
            paintFusionColourBar(
                painter, QRect(int(area.right()) - 96, int(area.center().y()) - h / 2, 88, h),
                overlayStyle_, overlayUnit_);
        }
        if (backend_ == Backend::Remote && lastProjection_) {
            paintTeachingMarks(painter, area, remote_->teachingMarks(), *lastProjection_);
        }
    }
    if (!notice_.isEmpty()) {
        painter.setPen(QColor(255, 200, 80));
        painter.drawText(area.adjusted(6, 4, -6, -4),
                         Qt::AlignLeft | Qt::AlignTop | Qt::TextWordWrap, notice_);
    }
}

void VolumeView::paintClipBox(QPainter& painter) const {
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing, true);
    // The device may have more pixels than the widget (high-DPI): draw in widget units.
    painter.scale(double(painter.device()->width()) / std::max(1, width()),
                  double(painter.device()->height()) / std::max(1, height()));
    const QSizeF viewSize(size());
    painter.setPen(QPen(QColor(255, 220, 60, 170), 1.0));
    for (const auto& [a, b] : clipEdges(volume_->geometry(), camera_, clip_, viewSize)) {
        if (a != b) {
            painter.drawLine(a, b);
        }
    }
    const ClipHandles handles = clipHandles();
    for (std::size_t n = 0; n < handles.size(); ++n) {
        if (!handles[n].visible) {
            continue;
        }
        const bool active = dragHandle_ == int(n);
        painter.setPen(QPen(QColor(255, 220, 60), 1.5));
        painter.setBrush(active ? QColor(255, 220, 60) : QColor(40, 40, 40, 160));
        painter.drawEllipse(handles[n].screen, kHandleRadius * 0.6, kHandleRadius * 0.6);
    }
    painter.restore();
}

void VolumeView::keyPressEvent(QKeyEvent* event) {
    if (event->key() == Qt::Key_B && event->modifiers() == Qt::NoModifier) {
        setClipHandlesShown(!clipHandlesShown_);
        return;
    }
    QWidget::keyPressEvent(event);
}

void VolumeView::mousePressEvent(QMouseEvent* event) {
    if (dragButton_ != Qt::NoButton) {
        return;
    }
    const Qt::MouseButton b = event->button();
    if (b != Qt::LeftButton && b != Qt::RightButton && b != Qt::MiddleButton) {
        return;
    }
    dragButton_ = b;
    lookAroundOnDrag();
    dragStart_ = event->position();
    dragCamera_ = camera_;
    dragClip_ = clip_;
    dragHandle_.reset();
    if (b == Qt::LeftButton && clipHandlesShown_) {
        dragHandle_ = hitClipHandle(clipHandles(), dragStart_, kHandleRadius);
    }
}

void VolumeView::mouseMoveEvent(QMouseEvent* event) {
    if (dragButton_ == Qt::NoButton) {
        return;
    }
    const QPointF d = event->position() - dragStart_;
    if (dragHandle_ && volume_) {
        const ClipHandles handles =
            lucent::clipHandles(volume_->geometry(), camera_, dragClip_, QSizeF(size()));
        const ClipBox moved =
            dragClipFace(dragClip_, handles[std::size_t(*dragHandle_)], d, volume_->dims());
        if (moved.lo != clip_.lo || moved.hi != clip_.hi) {
            setClipBox(moved);
        }
        return;
    }
    Camera c = dragCamera_;
    if (dragButton_ == Qt::LeftButton) {
        c.azimuth = dragCamera_.azimuth + d.x() * kDegreesPerPixel;
        c.elevation = std::clamp(dragCamera_.elevation + d.y() * kDegreesPerPixel, -90.0, 90.0);
    } else if (dragButton_ == Qt::RightButton) {
        c.zoom = std::clamp(dragCamera_.zoom * std::exp(-d.y() * kZoomPerPixel), 0.05, 50.0);
    } else {
        // What lies at the point looked at follows the mouse.
        const double mm = mmPerPixel(dragCamera_);
        c.panRight = dragCamera_.panRight - d.x() * mm;
        c.panUp = dragCamera_.panUp + d.y() * mm;
    }
    setCamera(c);
}

void VolumeView::mouseReleaseEvent(QMouseEvent* event) {
    if (event->button() != dragButton_) {
        return;
    }
    dragButton_ = Qt::NoButton;
    dragHandle_.reset();
    requestRender(); // the still frame, at full quality
}

void VolumeView::wheelEvent(QWheelEvent* event) {
    const double notches = event->angleDelta().y() / 120.0;
    if (notches == 0.0) {
        return;
    }
    Camera c = camera_;
    if (event->modifiers() & Qt::ShiftModifier) {
        // Towards the point looked at (and through it), never onto it.
        const double now = c.distance > 0.0
                               ? c.distance
                               : fitDistance(volume_ ? volume_->geometry() : VolumeGeometry{}, c,
                                             std::max(1, width()), std::max(1, height()));
        c.distance = std::max(now * std::pow(kDollyPerNotch, notches), 1e-3);
    } else {
        c.zoom = std::clamp(c.zoom * std::pow(kWheelZoomPerNotch, notches), 0.05, 50.0);
    }
    setCamera(c);
    event->accept();
}

} // namespace lucent
