#pragma once

#include <QObject>

#include "core/scene/Camera.h"

class QAction;
class QTimer;

namespace lucent {

class VolumeView;

// The 3D view's rotating MIP, the classic PET cine: MIP mode, the camera levelled and
// turned about the patient's head-foot axis, one frame every kRotatingMipFrameMs, a full
// turn in kRotatingMipFrames (rotatingMipCamera, core/scene/Turntable.h). A PET series
// (modality PT) is shown in inverted grey over its window (petMipTransferFunction), other
// series keep their transfer function. It stops on a key or a mouse button or the wheel in
// the view, on a camera or mode set by anything else, and when its action is triggered
// again; the view keeps the MIP and the camera it stopped at.
class RotatingMip : public QObject {
    Q_OBJECT

public:
    // A child of the view; the action is added to the view (its shortcut works there) and
    // goes into menus and the view's controls as it is.
    explicit RotatingMip(VolumeView* view);

    // Checkable "Rotating MIP", Ctrl+Shift+R: checked while it turns.
    QAction* action() const { return action_; }
    bool running() const;
    // Frames turned since it started.
    int frame() const { return frame_; }

public slots:
    void start();
    void stop();

signals:
    void runningChanged(bool running);

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    void nextFrame();

    VolumeView* view_;
    QTimer* timer_;
    QAction* action_;
    Camera start_;
    int frame_ = 0;
    bool turning_ = false; // the camera and mode being set are this one's own
};

} // namespace lucent
