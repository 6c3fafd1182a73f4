// RemoteRenderBackend: following a teaching session that another client
// presents (docs/protocol.md, "Teaching sessions", "Invites", "Free look").
#include <QWebSocket>

#include "protocol/ProtocolMessages.h"
#include "render/RemoteRenderBackend.h"

namespace lucent {

void RemoteRenderBackend::followSession(const SessionFollow& follow) {
    disconnectFromServer();
    presenting_ = false; // a follower presents nothing: the session is someone else's
    settings_ = {follow.url, follow.token, {}};
    if (const QString problem = follow.problem(); !problem.isEmpty()) {
        setStatus(BackendStatus::Failed, problem);
        return;
    }
    follow_ = follow;
    nextDelayMs_ = firstDelayMs_;
    open();
}

void RemoteRenderBackend::lookAround() {
    if (followState_ == FollowState::LookingAround) {
        return;
    }
    if (followState_ != FollowState::Following) {
        emit frameFailed(tr("cannot look around: not following a session"));
    } else if (serverVersion_ < 4) {
        emit frameFailed(tr("cannot look around: %1 speaks protocol version %2; free look needs "
                            "version 4")
                             .arg(where())
                             .arg(serverVersion_));
    } else {
        send(remote::writeClientMessage(remote::FreeLook{true}));
    }
}

void RemoteRenderBackend::backToTeacher() {
    if (followState_ == FollowState::LookingAround) {
        send(remote::writeClientMessage(remote::FreeLook{false}));
    }
}

void RemoteRenderBackend::setFollowState(FollowState state) {
    if (state != followState_) {
        followState_ = state;
        emit followStateChanged(state);
    }
}

bool RemoteRenderBackend::onFollowMessage(const remote::ServerMessage& message) {
    if (const auto* hello = std::get_if<remote::Hello>(&message)) {
        if (phase_ != Phase::Authenticating) {
            return false;
        }
        serverBackend_ = QString::fromStdString(hello->backend);
        serverVersion_ = hello->version;
        phase_ = Phase::Opening; // the session's series comes with `opened`
        if (!follow_->byInvite()) {
            send(remote::writeClientMessage(remote::SessionJoin{follow_->session.toStdString()}));
        }
        setStatus(BackendStatus::Connecting,
                  tr("joined a session on %1, waiting for its series").arg(where()));
    } else if (const auto* opened = std::get_if<remote::Opened>(&message)) {
        // The session's series, also when its presenter opens another.
        phase_ = Phase::Open;
        wasOpen_ = true;
        openSeries_ = QString::fromStdString(opened->series);
        nextDelayMs_ = firstDelayMs_;
        setFollowState(FollowState::Following);
        setStatus(BackendStatus::Connected, tr("following a session on %1, rendered with %2")
                                                .arg(where(), serverBackend_.section(',', 0, 0)));
    } else if (std::holds_alternative<remote::SessionLeft>(message)) {
        fail(tr("the session on %1 has ended").arg(where()));
    } else if (const auto* started = std::get_if<remote::FreeLookStarted>(&message)) {
        // From now on the frames are this client's own, counted from `seq`.
        seqSent_ = started->seq;
        firstViewSeq_ = started->seq;
        sent_.clear();
        refused_.clear();
        interacting_ = false;
        setFollowState(FollowState::LookingAround);
        Camera camera;
        camera.azimuth = started->azimuth;
        camera.elevation = started->elevation;
        camera.zoom = started->zoom;
        camera.distance = started->distance;
        camera.panRight = started->panRight;
        camera.panUp = started->panUp;
        emit lookAroundStarted(camera);
        sync();
    } else if (std::holds_alternative<remote::FreeLookEnded>(message)) {
        // The session's newest frame follows at once, then its frames again.
        cameraTimer_.stop();
        interacting_ = false;
        if (phase_ == Phase::Open) {
            setFollowState(FollowState::Following);
        }
    } else {
        return false;
    }
    return true;
}

bool RemoteRenderBackend::onFollowError(const QString& code, const QString& message) {
    if (code == "not-found" && phase_ != Phase::Open) {
        fail(tr("%1 has no session %2 to follow (%3)").arg(where(), follow_->session, message));
    } else if (code == "free-look-limit" || message.startsWith("free-look")) {
        emit frameFailed(tr("cannot look around: %1 (%2)").arg(message, code));
    } else if (code == "not-presenter" || code == "forbidden") {
        emit frameFailed(tr("a follower cannot do that: %1 (%2)").arg(message, code));
    } else {
        return false;
    }
    return true;
}

} // namespace lucent
