// VolumeView following a teaching session on a server: the session's frames
// with its pointer and marks, and looking around on a drag (free look).
#include "ui/volume/VolumeView.h"

namespace lucent {

void VolumeView::connectFollowing() {
    // Free look starts from the session's camera: the drag that started it turns
    // that camera from where the drag began.
    connect(remote_.get(), &RemoteRenderBackend::lookAroundStarted, this,
            [this](const Camera& camera) {
                dragCamera_ = camera;
                setCamera(camera);
            });
    connect(remote_.get(), &RemoteRenderBackend::followStateChanged, this, [this] {
        if (backend_ == Backend::Remote) {
            requestRender();
        }
    });
}

void VolumeView::followSession(const SessionFollow& follow) {
    if (backend_ != Backend::Remote) {
        useSurface(Backend::Remote);
    }
    remote_->followSession(follow);
    requestRender();
}

bool VolumeView::followsSession() const {
    return backend_ == Backend::Remote && remote_->followed().has_value();
}

void VolumeView::lookAroundOnDrag() {
    if (followsSession() && remote_->followState() == FollowState::Following) {
        remote_->lookAround();
    }
}

} // namespace lucent
