#include "ui/VolumeSurfaces.h"

#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QPainter>

#include "core/volume/BrickResidency.h"
#include "render/GlError.h"
#include "render/GpuRayCaster.h"
#include "ui/VolumeView.h"

namespace lucent {

VolumeGlSurface::VolumeGlSurface(VolumeView* view) : QOpenGLWidget(view), view_(view) {
    setFormat(VolumeView::surfaceFormat());
    setAttribute(Qt::WA_TransparentForMouseEvents);
}

VolumeGlSurface::~VolumeGlSurface() {
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
    }
}

void VolumeGlSurface::releaseGl() {
    if (!caster_) {
        return;
    }
    const bool madeCurrent = context() != nullptr;
    if (madeCurrent) {
        makeCurrent();
    }
    caster_.reset();
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
    const QSize deviceSize = size() * devicePixelRatioF();
    auto render = [this](const RenderDescription& d) {
        if (!caster_ || casterGeneration_ != view_->volumeGeneration()) {
            caster_.reset();
            caster_ = std::make_unique<GpuRayCaster>(*view_->volume());
            casterGeneration_ = view_->volumeGeneration();
        }
        RenderResult frame = caster_->render(d).frame;
        // The caster leaves its own framebuffer bound; QPainter draws into ours.
        QOpenGLFunctions* f = context()->functions();
        f->glBindFramebuffer(GL_FRAMEBUFFER, defaultFramebufferObject());
        f->glViewport(0, 0, width() * devicePixelRatio(), height() * devicePixelRatio());
        return frame;
    };
    try {
        QPainter painter(this);
        view_->paintFrame(painter, deviceSize, render);
    } catch (const GlError& e) {
        caster_.reset();
        reportFailure(QString::fromStdString(e.what()));
    } catch (const BudgetError& e) {
        caster_.reset();
        reportFailure(QString::fromStdString(e.what()));
    }
}

VolumeCpuSurface::VolumeCpuSurface(VolumeView* view) : QWidget(view), view_(view) {
    setAttribute(Qt::WA_TransparentForMouseEvents);
    setAttribute(Qt::WA_OpaquePaintEvent);
}

void VolumeCpuSurface::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    try {
        view_->paintFrame(
            painter, size() * devicePixelRatioF(),
            [this](const RenderDescription& d) { return view_->cpuCaster().render(d); });
    } catch (const std::exception& e) {
        painter.setPen(QColor(255, 120, 80));
        painter.drawText(rect().adjusted(6, 4, -6, -4), Qt::AlignLeft | Qt::AlignTop,
                         tr("Cannot render: %1").arg(QString::fromStdString(e.what())));
    }
}

} // namespace lucent
