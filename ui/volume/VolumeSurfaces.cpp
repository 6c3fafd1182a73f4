#include "ui/volume/VolumeSurfaces.h"

#include <QOpenGLContext>
#include <QPainter>

#include "render/GpuRayCaster.h"
#include "ui/volume/VolumeView.h"

namespace lucent {

VolumeGlSurface::VolumeGlSurface(VolumeView* view) : QOpenGLWidget(view), view_(view) {
    setFormat(VolumeView::surfaceFormat());
    setAttribute(Qt::WA_TransparentForMouseEvents);
}

VolumeGlSurface::~VolumeGlSurface() {
    // QOpenGLWidget's destructor destroys the context after this one has run:
    // its aboutToBeDestroyed must not reach a VolumeGlSurface that is gone.
    if (QOpenGLContext* c = context()) {
        disconnect(c, &QOpenGLContext::aboutToBeDestroyed, this, nullptr);
    }
    releaseGl();
}

void VolumeGlSurface::initializeGL() {
    // A widget moved to another window gets a new context: the old one takes
    // the caster's textures and buffers with it, so they go first.
    connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, &VolumeGlSurface::contextGoing,
            Qt::UniqueConnection);
    const QSurfaceFormat f = context()->format();
    if (f.version() < qMakePair(4, 3) || f.profile() != QSurfaceFormat::CoreProfile) {
        reportFailure(
            tr("OpenGL %1.%2 %3 context; the GPU renderer needs 4.3 core")
                .arg(f.majorVersion())
                .arg(f.minorVersion())
                .arg(f.profile() == QSurfaceFormat::CoreProfile ? "core" : "compatibility"));
        return;
    }
    // A new context (first show, or another window): render afresh in it.
    view_->requestRender();
}

void VolumeGlSurface::contextGoing() {
    // The frame lives in this context's framebuffer: read it back while it can
    // be, so that the view's lastFrame() still has it (a new context renders
    // afresh anyway, uploading every brick again).
    view_->lastFrame();
    releaseGl();
}

void VolumeGlSurface::releaseGl() {
    if (!view_->localBackend().holdsGlResources()) {
        return;
    }
    const bool madeCurrent = context() != nullptr;
    if (madeCurrent) {
        makeCurrent();
    }
    view_->localBackend().releaseGl();
    if (madeCurrent) {
        doneCurrent();
    }
}

void VolumeGlSurface::reportFailure(const QString& reason) {
    if (failed_) {
        return;
    }
    failed_ = true;
    // Not now: this widget is in the middle of painting and the view replaces it.
    QMetaObject::invokeMethod(
        view_, [view = view_, reason] { view->fallBackToCpu(reason); }, Qt::QueuedConnection);
}

void VolumeGlSurface::paintGL() {
    // The frame goes straight into this widget's framebuffer; the overlays over it.
    const QSize pixels = size() * devicePixelRatio();
    const FramebufferTarget target{defaultFramebufferObject(), 0, 0, pixels.width(),
                                   pixels.height()};
    // QOpenGLWidget always renders into its own framebuffer object; none means
    // the platform could not give it one, and framebuffer 0 is not ours to draw in.
    if (target.framebuffer == 0 && !failed_) {
        reportFailure(tr("the OpenGL widget got no framebuffer on this platform"));
    }
    if (failed_) {
        if (target.framebuffer == 0) {
            return;
        }
        try {
            clearFramebuffer(target, glm::dvec3(0.0));
        } catch (const std::exception&) {
            // The view is being handed over to the CPU renderer already.
        }
        return;
    }
    view_->drawFrameInPlace(target);
    QPainter painter(this);
    view_->paintFrame(painter);
}

ImageRGBA8 VolumeGlSurface::readLastFrame() {
    if (context() == nullptr) {
        return {};
    }
    // From paintGL (a slot of renderedFrame) the context is current already.
    const bool wasCurrent = QOpenGLContext::currentContext() == context();
    if (!wasCurrent) {
        makeCurrent();
    }
    ImageRGBA8 image;
    try {
        image = view_->localBackend().readLastFrame();
    } catch (const std::exception&) {
        // Nothing to read: the next frame says why, if OpenGL failed.
    }
    if (!wasCurrent) {
        doneCurrent();
    }
    return image;
}

VolumeFrameSurface::VolumeFrameSurface(VolumeView* view) : QWidget(view), view_(view) {
    setAttribute(Qt::WA_TransparentForMouseEvents);
    setAttribute(Qt::WA_OpaquePaintEvent);
}

void VolumeFrameSurface::paintEvent(QPaintEvent*) {
    view_->renderPending();
    QPainter painter(this);
    view_->paintFrame(painter);
}

} // namespace lucent
