#pragma once
// The two render surfaces of VolumeView: they show frames and pass every mouse
// event through to the view (which owns camera and interaction).

#include <cstdint>
#include <memory>

#include <QOpenGLWidget>
#include <QWidget>

namespace lucent {

class GpuRayCaster;
class VolumeView;

// Renders with GpuRayCaster in this widget's context. The caster is made in
// paintGL for the view's current volume and released with the context
// (aboutToBeDestroyed, or this widget's destruction), with the context current.
// A GL failure hands the view over to the CPU renderer.
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
    std::unique_ptr<GpuRayCaster> caster_;
    std::uint64_t casterGeneration_ = 0;
    bool failed_ = false;
};

// Renders with the view's CpuRayCaster and paints with QPainter.
class VolumeCpuSurface : public QWidget {
    Q_OBJECT

public:
    explicit VolumeCpuSurface(VolumeView* view);

protected:
    void paintEvent(QPaintEvent* event) override;

private:
    VolumeView* view_;
};

} // namespace lucent
