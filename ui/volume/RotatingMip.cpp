#include "ui/volume/RotatingMip.h"

#include <QAction>
#include <QEvent>
#include <QKeyEvent>
#include <QTimer>

#include "core/pet/PetProjection.h"
#include "core/scene/Turntable.h"
#include "ui/volume/VolumeView.h"

namespace lucent {

namespace {

bool isModifierKey(int key) {
    return key == Qt::Key_Shift || key == Qt::Key_Control || key == Qt::Key_Alt ||
           key == Qt::Key_Meta || key == Qt::Key_AltGr;
}

} // namespace

RotatingMip::RotatingMip(VolumeView* view)
    : QObject(view), view_(view), timer_(new QTimer(this)), action_(new QAction(this)) {
    action_->setText(tr("Rotating &MIP"));
    action_->setObjectName(QStringLiteral("rotatingMip"));
    action_->setShortcut(QKeySequence(tr("Ctrl+Shift+R")));
    action_->setToolTip(tr("Turn a MIP about the head-foot axis (the PET cine); a key or a "
                           "click in the 3D view stops it"));
    action_->setCheckable(true);
    view_->addAction(action_);
    connect(action_, &QAction::triggered, this, [this](bool checked) {
        if (checked) {
            start();
        } else {
            stop();
        }
    });
    timer_->setTimerType(Qt::PreciseTimer); // a steady turn
    timer_->setInterval(kRotatingMipFrameMs);
    connect(timer_, &QTimer::timeout, this, &RotatingMip::nextFrame);
    connect(view_, &VolumeView::cameraChanged, this, [this] {
        if (!turning_) {
            stop();
        }
    });
    connect(view_, &VolumeView::modeChanged, this, [this](RenderMode mode) {
        if (!turning_ && mode != RenderMode::Mip) {
            stop();
        }
    });
    connect(view_, &VolumeView::volumeChanged, this, &RotatingMip::stop);
    view_->installEventFilter(this);
}

bool RotatingMip::running() const {
    return timer_->isActive();
}

void RotatingMip::start() {
    const auto& volume = view_->volume();
    if (running() || !volume || volume->empty()) {
        action_->setChecked(running());
        return;
    }
    turning_ = true;
    view_->setMode(RenderMode::Mip);
    if (volume->modality == "PT") {
        view_->setTransferFunction(petMipTransferFunction(*volume));
    }
    start_ = view_->camera();
    frame_ = 0;
    view_->setCamera(rotatingMipCamera(start_, frame_));
    turning_ = false;
    timer_->start();
    action_->setChecked(true);
    emit runningChanged(true);
}

void RotatingMip::stop() {
    if (!running()) {
        action_->setChecked(false);
        return;
    }
    timer_->stop();
    action_->setChecked(false);
    emit runningChanged(false);
}

void RotatingMip::nextFrame() {
    ++frame_;
    turning_ = true;
    view_->setCamera(rotatingMipCamera(start_, frame_));
    turning_ = false;
}

bool RotatingMip::eventFilter(QObject* watched, QEvent* event) {
    if (watched == view_ && running()) {
        const QEvent::Type type = event->type();
        const bool key =
            type == QEvent::KeyPress && !isModifierKey(static_cast<QKeyEvent*>(event)->key());
        if (key || type == QEvent::MouseButtonPress || type == QEvent::Wheel) {
            stop(); // the event goes on: a drag after it turns the view by hand
        }
    }
    return QObject::eventFilter(watched, event);
}

} // namespace lucent
