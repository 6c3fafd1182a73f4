// ClientConnection: teaching sessions: session-create, session-join,
// session-handover and session-leave; joining, leaving, and a session's end.
#include "server/ClientConnection.h"
#include "server/ClientConnection_p.h"
#include "server/RenderServer.h"
#include "server/TeachingSession.h"
#include "server/ViewStream.h"

namespace lucent::remote {

void ClientConnection::handleSession(const ClientMessage& message) {
    if (std::holds_alternative<SessionCreate>(message)) {
        if (session_) {
            sendError("out-of-order", "already in a session", true);
            return;
        }
        TeachingSession* session = server_.createSession(*this);
        if (!session) {
            sendError("session-limit", "the server runs as many sessions as it may", false);
            return;
        }
        const auto shared = ownView_->series();
        ownView_->close();
        session_ = session;
        sendJson(writeServerMessage(SessionCreated{session->id().toStdString()}));
        session->broadcastState();
        if (shared) {
            session->share(shared); // the series this client had open, de-identified
        }
    } else if (const auto* join = std::get_if<SessionJoin>(&message)) {
        if (session_) {
            sendError("out-of-order", "already in a session", true);
            return;
        }
        TeachingSession* session = server_.findSession(QString::fromStdString(join->session));
        if (!session) {
            sendError("not-found", "no such session", false);
            return;
        }
        if (session->full()) {
            sendError("session-full", "the session has no room for another member", false);
            return;
        }
        joinSession(*session);
    } else if (const auto* handover = std::get_if<SessionHandover>(&message)) {
        const ClientConnection* to = session_ ? session_->member(handover->to) : nullptr;
        if (!session_) {
            sendError("out-of-order", "not in a session", true);
        } else if (!session_->isPresenter(*this)) {
            sendError("not-presenter", "this client does not hold control of the session", false);
        } else if (to && to->invite() != 0) {
            sendError("forbidden",
                      "session-handover: member " + std::to_string(handover->to) +
                          " joined by invite and may only follow",
                      false);
        } else if (!session_->handover(handover->to)) {
            sendError("bad-request", "session-handover: no member " + std::to_string(handover->to),
                      false);
        } else {
            session_->broadcastState();
        }
    } else if (std::holds_alternative<SessionLeave>(message)) {
        if (!session_) {
            sendError("out-of-order", "not in a session", true);
            return;
        }
        const std::string id = session_->id().toStdString();
        leaveSession();
        sendJson(writeServerMessage(SessionLeft{id}));
        if (invite_ != 0) {
            closeNormally("left"); // an invite's holder can do nothing else
        }
    }
}

void ClientConnection::joinSession(TeachingSession& session) {
    ownView_->close();
    session_ = &session;
    session.join(*this);
    session.broadcastState();
    qCInfo(lcClient) << "client" << id_ << "joined a session" << (invite_ ? "by invite" : "");
}

void ClientConnection::sessionEnded(const std::string& sessionId) {
    session_ = nullptr;
    sendJson(writeServerMessage(SessionLeft{sessionId}));
    if (invite_ != 0) {
        closeNormally("session ended");
    }
}

void ClientConnection::leaveSession() {
    if (!session_) {
        return;
    }
    TeachingSession* session = session_;
    session_ = nullptr;
    if (session->leave(*this)) {
        server_.endSession(session->id());
    } else {
        session->broadcastState();
    }
}

} // namespace lucent::remote
