#pragma once
// The two render surfaces of VolumeView: they show frames and pass every mouse
// event through to the view (which owns camera and interaction).

#include <QOpenGLWidget>
#include <QWidget>

#include "core/image/Image.h"

namespace lucent {

class VolumeView;

// Gives the view's LocalRenderBackend this widget's context: the backend's
// GPU ray caster draws each frame straight into this widget's framebuffer in
// paintGL (no read back), the view's overlays are painted over it with
// QPainter, and the caster is released with the context (aboutToBeDestroyed,
// or this widget's destruction), with the context current. A context older
// than 4.3 core hands the view over to the CPU renderer.
class VolumeGlSurface : public QOpenGLWidget {
    Q_OBJECT

public:
    explicit VolumeGlSurface(VolumeView* view);
    ~VolumeGlSurface() override;

    // The last frame drawn, read back in this widget's context (rendered
    // again, as it was rendered: an interactive frame at its smaller size);
    // empty when there is none or OpenGL fails.
    ImageRGBA8 readLastFrame();

protected:
    void initializeGL() override;
    void paintGL() override;

private:
    void contextGoing();
    void releaseGl();
    void reportFailure(const QString& reason);

    VolumeView* view_;
    bool failed_ = false;
};

// Paints frames with QPainter: the CPU ray caster's (rendered in the paint) or
// a render server's (as they arrive).
class VolumeFrameSurface : public QWidget {
    Q_OBJECT

public:
    explicit VolumeFrameSurface(VolumeView* view);

protected:
    void paintEvent(QPaintEvent* event) override;

private:
    VolumeView* view_;
};

} // namespace lucent
