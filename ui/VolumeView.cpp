#include "ui/VolumeView.h"

#include <algorithm>
#include <cmath>

#include <QMouseEvent>
#include <QOpenGLContext>
#include <QPainter>
#include <QStackedLayout>
#include <QWheelEvent>

#include "ui/VolumeSurfaces.h"

namespace lucent {

namespace {

// Why a 4.3 core context cannot be made here; empty when it can.
QString glUnavailableReason() {
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
    : QWidget(parent), transferFunction_(defaultTransferFunction(nullptr)) {
    setMinimumSize(120, 120);
    setFocusPolicy(Qt::StrongFocus);
    auto* layout = new QStackedLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    if (preferred == Backend::Gpu) {
        glFailure_ = glUnavailableReason();
    } else {
        glFailure_ = tr("the CPU renderer was chosen");
    }
    useSurface(glFailure_.isEmpty() ? Backend::Gpu : Backend::Cpu);
}

VolumeView::~VolumeView() = default;

QSurfaceFormat VolumeView::surfaceFormat() {
    QSurfaceFormat format = QSurfaceFormat::defaultFormat();
    if (format.version() < qMakePair(4, 3) || format.profile() != QSurfaceFormat::CoreProfile) {
        format.setVersion(4, 3);
        format.setProfile(QSurfaceFormat::CoreProfile);
    }
    return format;
}

void VolumeView::useSurface(Backend backend) {
    auto* layout = static_cast<QStackedLayout*>(this->layout());
    if (surface_ != nullptr) {
        layout->removeWidget(surface_);
        surface_->hide();
        surface_->deleteLater();
    }
    backend_ = backend;
    if (backend == Backend::Gpu) {
        surface_ = new VolumeGlSurface(this);
        setNotice({});
    } else {
        surface_ = new VolumeCpuSurface(this);
        setNotice(tr("3D on the CPU: %1").arg(glFailure_));
    }
    layout->addWidget(surface_);
    layout->setCurrentWidget(surface_);
}

void VolumeView::fallBackToCpu(const QString& reason) {
    if (backend_ == Backend::Cpu) {
        return;
    }
    glFailure_ = reason;
    useSurface(Backend::Cpu);
}

void VolumeView::setNotice(const QString& notice) {
    if (notice != notice_) {
        notice_ = notice;
        emit noticeChanged(notice_);
    }
}

CpuRayCaster& VolumeView::cpuCaster() {
    if (!cpuCaster_ || cpuCasterGeneration_ != volumeGeneration_) {
        cpuCaster_.reset();
        cpuCaster_ = std::make_unique<CpuRayCaster>(*volume_);
        cpuCasterGeneration_ = volumeGeneration_;
    }
    return *cpuCaster_;
}

void VolumeView::setVolume(std::shared_ptr<const Volume> volume) {
    // The GL surface's caster is remade on its next frame, in its own context.
    cpuCaster_.reset();
    volume_ = std::move(volume);
    ++volumeGeneration_;
    transferFunction_ = defaultTransferFunction(volume_.get());
    clip_ = ClipBox{};
    pan_ = {};
    camera_ = Camera{};
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
    pan_ = {};
    setCamera(Camera{});
}

void VolumeView::setMode(RenderMode mode) {
    mode_ = mode;
    requestRender();
}

void VolumeView::setIsoValue(double value) {
    isoValue_ = value;
    requestRender();
}

void VolumeView::setClipBox(const ClipBox& clip) {
    clip_ = clip;
    requestRender();
}

void VolumeView::setSampling(const SamplingSettings& sampling) {
    sampling_ = sampling;
    requestRender();
}

void VolumeView::setPan(const QPointF& pan) {
    pan_ = pan;
    requestRender();
}

void VolumeView::requestRender() {
    if (surface_ != nullptr) {
        surface_->update();
    }
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
    d.isoValue = isoValue_;
    d.clip = clip_;
    d.sampling = sampling_;
    d.width = width;
    d.height = height;
    return d;
}

QImage VolumeView::grabImage() {
    if (auto* gl = qobject_cast<VolumeGlSurface*>(surface_)) {
        return gl->grabFramebuffer();
    }
    return surface_->grab().toImage();
}

void VolumeView::paintFrame(QPainter& painter, const QSize& deviceSize,
                            const FrameRenderer& render) {
    const QRectF area(QPointF(0, 0), QSizeF(painter.device()->width(), painter.device()->height()));
    painter.fillRect(area, Qt::black);
    if (!volume_ || volume_->empty()) {
        painter.setPen(Qt::gray);
        painter.drawText(area, Qt::AlignCenter, tr("No volume"));
        return;
    }
    const RenderDescription still =
        description(std::max(1, deviceSize.width()), std::max(1, deviceSize.height()));
    const bool interactive = interacting();
    QString renderError;
    try {
        RenderResult frame = render(interactive ? interactiveDescription(still, quality_) : still);
        lastFrame_ =
            interactive ? scaledTo(frame.image, still.width, still.height) : std::move(frame.image);
        const QImage image(lastFrame_.pixels.data(), lastFrame_.width, lastFrame_.height,
                           4 * lastFrame_.width, QImage::Format_RGBA8888);
        painter.setRenderHint(QPainter::SmoothPixmapTransform, false);
        painter.drawImage(QRectF(pan_, area.size()), image);
        emit renderedFrame(frame.stats, interactive);
    } catch (const std::invalid_argument& e) {
        renderError = tr("Cannot render: %1").arg(QString::fromStdString(e.what()));
    }
    const QString line = renderError.isEmpty() ? notice_ : renderError;
    if (!line.isEmpty()) {
        painter.setPen(QColor(255, 200, 80));
        painter.drawText(area.adjusted(6, 4, -6, -4), Qt::AlignLeft | Qt::AlignTop, line);
    }
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
    dragStart_ = event->position();
    dragCamera_ = camera_;
    dragPan_ = pan_;
}

void VolumeView::mouseMoveEvent(QMouseEvent* event) {
    if (dragButton_ == Qt::NoButton) {
        return;
    }
    const QPointF d = event->position() - dragStart_;
    Camera c = dragCamera_;
    if (dragButton_ == Qt::LeftButton) {
        c.azimuth = dragCamera_.azimuth + d.x() * kDegreesPerPixel;
        c.elevation = std::clamp(dragCamera_.elevation + d.y() * kDegreesPerPixel, -90.0, 90.0);
    } else if (dragButton_ == Qt::RightButton) {
        c.zoom = std::clamp(dragCamera_.zoom * std::exp(-d.y() * kZoomPerPixel), 0.05, 50.0);
    } else {
        pan_ = dragPan_ + d;
    }
    setCamera(c);
}

void VolumeView::mouseReleaseEvent(QMouseEvent* event) {
    if (event->button() != dragButton_) {
        return;
    }
    dragButton_ = Qt::NoButton;
    requestRender(); // the still frame, at full quality
}

void VolumeView::wheelEvent(QWheelEvent* event) {
    const double notches = event->angleDelta().y() / 120.0;
    if (notches == 0.0) {
        return;
    }
    Camera c = camera_;
    c.zoom = std::clamp(c.zoom * std::pow(kWheelZoomPerNotch, notches), 0.05, 50.0);
    setCamera(c);
    event->accept();
}

} // namespace lucent
