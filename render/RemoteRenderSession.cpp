// RemoteRenderBackend: presenting a teaching session and inviting students to
// it (docs/protocol.md, "Teaching sessions" and "Invites").
#include <QWebSocket>

#include "protocol/ProtocolMessages.h"
#include "render/RemoteRenderBackend.h"

namespace lucent {

void RemoteRenderBackend::setPresenting(bool presenting) {
    if (presenting == presenting_) {
        return;
    }
    if (presenting && follow_) { // the session followed is someone else's
        emit inviteRefused(
            tr("this view follows a session on %1; it cannot present one").arg(where()));
        return;
    }
    presenting_ = presenting;
    if (socket_ || reconnectTimer_.isActive()) {
        // A session starts on a new connection; leaving one ends it (this is its
        // only token holder) and drops the students its invites let in.
        closeConnection();
        nextDelayMs_ = firstDelayMs_;
        open();
    }
}

void RemoteRenderBackend::createInvite(std::optional<std::int64_t> lifetimeSeconds) {
    if (sessionId_.isEmpty()) {
        emit inviteRefused(tr("not presenting a session on %1").arg(where()));
    } else if (serverVersion_ < 3) {
        emit inviteRefused(tr("%1 speaks protocol version %2; invites need version 3")
                               .arg(where())
                               .arg(serverVersion_));
    } else {
        send(remote::writeClientMessage(remote::InviteCreate{lifetimeSeconds, std::nullopt}));
    }
}

void RemoteRenderBackend::revokeInvite(std::uint64_t invite) {
    if (!sessionId_.isEmpty() && serverVersion_ >= 3) {
        send(remote::writeClientMessage(remote::InviteRevoke{invite}));
    }
}

void RemoteRenderBackend::recallFreeLook() {
    if (!sessionId_.isEmpty() && serverVersion_ >= 4) {
        send(remote::writeClientMessage(remote::FreeLookRecall{}));
    }
}

bool RemoteRenderBackend::onSessionMessage(const remote::ServerMessage& message) {
    if (const auto* created = std::get_if<remote::SessionCreated>(&message)) {
        setSessionId(QString::fromStdString(created->session));
    } else if (const auto* looks = std::get_if<remote::FreeLookState>(&message)) {
        emit freeLookChanged(looks->looking, looks->limit);
    } else if (const auto* invite = std::get_if<remote::InviteCreated>(&message)) {
        emit inviteCreated(*invite);
    } else if (const auto* revoked = std::get_if<remote::InviteRevoked>(&message)) {
        emit inviteRevoked(revoked->invite);
    } else if (marks_.apply(message)) {
        emit marksChanged();
    } else {
        return false;
    }
    return true;
}

void RemoteRenderBackend::point(std::optional<glm::dvec2> at) {
    if (!sessionId_.isEmpty() && serverVersion_ >= 4) {
        send(remote::writeClientMessage(remote::PointerUpdate{at}));
    }
}

void RemoteRenderBackend::placeMark(const remote::MarkPlace& mark) {
    if (!sessionId_.isEmpty() && serverVersion_ >= 4) {
        send(remote::writeClientMessage(mark));
    }
}

void RemoteRenderBackend::clearMarks() {
    if (!sessionId_.isEmpty() && serverVersion_ >= 4) {
        send(remote::writeClientMessage(remote::MarksClear{}));
    }
}

bool RemoteRenderBackend::isInviteRefusal(const QString& code, const QString& message) const {
    return code == "invite-limit" || message.startsWith("invite-create") ||
           message.startsWith("invite-revoke");
}

void RemoteRenderBackend::setSessionId(const QString& id) {
    if (id != sessionId_) {
        sessionId_ = id;
        emit freeLookChanged(0, 0); // a new session (or none): no one looks on their own yet
        emit sessionChanged(id);
    }
}

} // namespace lucent
