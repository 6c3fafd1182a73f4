#pragma once
// The two render surfaces of VolumeView: they show frames and pass every mouse
// event through to the view (which owns camera and interaction).

#include <QOpenGLWidget>
#include <QWidget>

namespace lucent {

class VolumeView;

// Gives the view's LocalRenderBackend this widget's context: the backend's
// GpuRayCaster renders in paintGL and is released with the context
// (aboutToBeDestroyed, or this widget's destruction), with the context current.
// A context older than 4.3 core hands the view over to the CPU renderer.
class VolumeGlSurface : public QOpenGLWidget {
    Q_OBJECT

public:
    explicit VolumeGlSurface(VolumeView* view);
    ~VolumeGlSurface() override;

protected:
    void initializeGL() override;
    void paintGL() override;

private:
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
