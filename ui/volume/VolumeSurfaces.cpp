#include "ui/volume/VolumeSurfaces.h"

#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QPainter>

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
    connect(context(), &QOpenGLContext::aboutToBeDestroyed, this, &VolumeGlSurface::releaseGl,
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
    QOpenGLFunctions* gl = context()->functions();
    gl->glClearColor(0.f, 0.f, 0.f, 1.f);
    gl->glClear(GL_COLOR_BUFFER_BIT);
    if (failed_) {
        return;
    }
    view_->renderPending();
    // The caster leaves its own framebuffer bound; QPainter draws into ours.
    gl->glBindFramebuffer(GL_FRAMEBUFFER, defaultFramebufferObject());
    gl->glViewport(0, 0, width() * devicePixelRatio(), height() * devicePixelRatio());
    QPainter painter(this);
    view_->paintFrame(painter);
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
