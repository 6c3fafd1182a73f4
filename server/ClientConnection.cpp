#include "server/ClientConnection.h"

#include <QLoggingCategory>
#include <QWebSocketHandshakeOptions>

#include "server/ClientConnection_p.h"
#include "server/RecordingReplay.h"
#include "server/RenderServer.h"
#include "server/SessionRecorder.h"
#include "server/TeachingSession.h"
#include "server/ViewStream.h"

namespace lucent::remote {

Q_LOGGING_CATEGORY(lcClient, "lucent.server.client")

namespace {

// The subprotocols the client offered in its handshake.
QStringList offeredSubprotocols(const QWebSocket& socket) {
    QStringList offered = socket.handshakeOptions().subprotocols();
    const QByteArray header = socket.request().rawHeader("Sec-WebSocket-Protocol");
    for (const QByteArray& part : header.split(',')) {
        const QString name = QString::fromLatin1(part.trimmed());
        if (!name.isEmpty() && !offered.contains(name)) {
            offered.append(name);
        }
    }
    return offered;
}

// The version the handshake selected (Qt's server picks one of
// supportedSubprotocols() that the client offered); 1 when none.
int connectionVersion(const QWebSocket& socket) {
    return subprotocolVersion(socket.subprotocol().toStdString()).value_or(kOldestProtocolVersion);
}

} // namespace

ClientConnection::ClientConnection(quint64 id, QWebSocket* socket, RenderServer& server)
    : QObject(&server), id_(id), version_(connectionVersion(*socket)), socket_(socket),
      server_(server), ownView_(new ViewStream(server.newViewId(), server, this)) {
    socket->setParent(this);
    ownView_->addMember(this);
    ownView_->setPacer(this);
    // Qt closes the connection itself beyond this; below it the protocol's
    // own limit answers with an error message first. The frame limit makes
    // Qt refuse a huge frame from its header instead of buffering it whole.
    socket->setMaxAllowedIncomingFrameSize(kMaxIncomingWebSocketBytes);
    socket->setMaxAllowedIncomingMessageSize(kMaxIncomingWebSocketBytes);
    connect(socket, &QWebSocket::textMessageReceived, this, &ClientConnection::onText);
    connect(socket, &QWebSocket::binaryMessageReceived, this, &ClientConnection::onBinary);
    connect(socket, &QWebSocket::bytesWritten, this, &ClientConnection::onBytesWritten);
    connect(socket, &QWebSocket::disconnected, this, [this] {
        qCInfo(lcClient) << "client" << id_ << "disconnected";
        closing_ = true;
        viewChanging();
        leaveSession();
        emit closed(id_);
    });
    authTimer_.setSingleShot(true);
    connect(&authTimer_, &QTimer::timeout, this,
            [this] { sendError("auth-timeout", "no auth message within the time allowed", true); });
    authTimer_.start(kAuthTimeoutMs);
    cameraClock_.start();
    lastHeard_.start();
    connect(socket, &QWebSocket::pong, this, [this] { lastHeard_.restart(); });
    connect(&keepaliveTimer_, &QTimer::timeout, this, &ClientConnection::onKeepalive);
    keepaliveTimer_.start(1000 * server.keepaliveSeconds());
}

void ClientConnection::onKeepalive() {
    if (!socket_ || closing_) {
        return;
    }
    if (lastHeard_.elapsed() > 3 * keepaliveTimer_.interval()) {
        qCInfo(lcClient) << "client" << id_ << "silent; dropped";
        socket_->abort(); // disconnected() follows: it leaves its session
        return;
    }
    socket_->ping();
}

void ClientConnection::start() {
    if (!socket_) {
        return;
    }
    const QString tokenPrefix = QString::fromLatin1(kTokenSubprotocolPrefix);
    const QString invitePrefix = QString::fromLatin1(kInviteSubprotocolPrefix);
    for (const QString& offered : offeredSubprotocols(*socket_)) {
        if (offered.startsWith(tokenPrefix)) {
            authenticate(offered.mid(tokenPrefix.size()).toStdString());
            break;
        }
        if (offered.startsWith(invitePrefix)) {
            authenticateInvite(offered.mid(invitePrefix.size()).toStdString());
            break;
        }
    }
}

ClientConnection::~ClientConnection() {
    closing_ = true;         // nothing more is sent
    stopRecording("closed"); // the server stops: what was recorded is kept
}

void ClientConnection::sendJson(const std::string& json) {
    if (socket_ && !closing_) {
        socket_->sendTextMessage(QString::fromStdString(json));
    }
}

void ClientConnection::sendError(const std::string& code, const std::string& message, bool fatal) {
    if (!socket_ || closing_) {
        return;
    }
    qCInfo(lcClient) << "client" << id_ << "error" << code.c_str() << (fatal ? "(closing)" : "");
    sendJson(errorReply(code, message, fatal));
    if (fatal) {
        closing_ = true;
        socket_->flush();
        // 1009 for a message too large, 1008 for any other broken rule.
        socket_->close(code == "too-large" ? QWebSocketProtocol::CloseCodeTooMuchData
                                           : QWebSocketProtocol::CloseCodePolicyViolated,
                       QString::fromStdString(code));
    }
}

void ClientConnection::offerFrame(const QByteArray& message, int channel) {
    if (!socket_ || closing_) {
        return;
    }
    if (socket_->bytesToWrite() == 0 && pendingFrames_.empty()) {
        socket_->sendBinaryMessage(message);
    } else {
        pendingFrames_[channel] = message; // a newer frame replaces the one waiting
    }
}

bool ClientConnection::readyForFrame() const {
    return socket_ && !closing_ && socket_->bytesToWrite() == 0 && pendingFrames_.empty();
}

void ClientConnection::onBytesWritten() {
    if (!socket_ || closing_) {
        return;
    }
    if (!pendingFrames_.empty() && socket_->bytesToWrite() == 0) {
        for (const auto& [channel, frame] : std::exchange(pendingFrames_, {})) {
            socket_->sendBinaryMessage(frame);
        }
    }
    (session_ ? session_->viewOf(*this) : *ownView_).pump();
}

void ClientConnection::onBinary(const QByteArray&) {
    sendError("malformed", "binary messages are not part of the client's protocol", true);
}

void ClientConnection::onText(const QString& text) {
    if (closing_) {
        return;
    }
    lastHeard_.restart();
    const QByteArray utf8 = text.toUtf8();
    try {
        handle(parseClientMessage(std::string_view(utf8.constData(), std::size_t(utf8.size())),
                                  version_));
    } catch (const ProtocolError& e) {
        sendError(e.code(), e.what(), e.fatal());
    }
}

void ClientConnection::authenticate(const std::string& token) {
    if (!server_.acceptsToken(token)) {
        sendError("auth-failed", "the token is not valid", true);
        return;
    }
    authenticated_ = true;
    authTimer_.stop();
    qCInfo(lcClient) << "client" << id_ << "authenticated, protocol version" << version_;
    sendJson(writeServerMessage(helloFor(version_, server_.backendDescription().toStdString())));
}

void ClientConnection::handle(const ClientMessage& message) {
    if (!authenticated_) {
        if (const auto* auth = std::get_if<AuthRequest>(&message)) {
            if (auth->invite.empty()) {
                authenticate(auth->token);
            } else {
                authenticateInvite(auth->invite);
            }
        } else {
            sendError("auth-required",
                      "the first message must be {\"type\":\"auth\",\"token\":...}", true);
        }
        return;
    }
    const bool follower = session_ && !session_->isPresenter(*this);
    if (std::holds_alternative<AuthRequest>(message)) {
        sendError("out-of-order", "already authenticated", true);
    } else if (refusedToInvitee(message)) {
        return;
    } else if (std::holds_alternative<InviteCreate>(message) ||
               std::holds_alternative<InviteRevoke>(message)) {
        handleInvite(message);
    } else if (handleMark(message)) {
        return;
    } else if (std::holds_alternative<ListRequest>(message)) {
        sendList();
    } else if (const auto* open = std::get_if<OpenRequest>(&message)) {
        if (follower) {
            sendError("not-presenter", "this client does not hold control of the session", false);
        } else {
            handleOpen(*open);
        }
    } else if (std::holds_alternative<FreeLook>(message) ||
               std::holds_alternative<FreeLookRecall>(message)) {
        handleFreeLook(message);
    } else if (const auto* slices = std::get_if<SlicesRequest>(&message)) {
        ViewStream& view = session_ ? session_->view() : *ownView_;
        if (follower) {
            sendError("not-presenter", "this client does not hold control of the session", false);
        } else if (!view.accepting()) {
            sendError("out-of-order", "open a series first", true);
        } else {
            view.slices().apply(*slices);
        }
    } else if (isRecordingControl(message)) {
        handleRecording(message);
    } else if (!isViewMessage(message)) {
        viewChanging(); // session-create, -join, -leave, -handover
        handleSession(message);
    } else if (ViewStream* controlled = controlledView(message); !controlled) {
        sendError("not-presenter", "this client does not hold control of the session", false);
    } else {
        ViewStream& view = *controlled;
        if (!view.accepting()) {
            sendError("out-of-order", "open a series first", true);
            return;
        }
        if (std::holds_alternative<CameraUpdate>(message) && !takeCameraToken()) {
            sendError("rate-limited", "too many camera updates; this one was dropped", false);
            return;
        }
        stopReplay("view"); // the presenter takes the view back
        if (const auto error = view.apply(message)) {
            sendError("bad-request", *error, false);
        } else {
            if (session_ && !follower) {
                session_->freeLook().follow(message);
            }
            recordAccepted(message);
        }
    }
}

void ClientConnection::closeNormally(const QString& reason) {
    if (!socket_ || closing_) {
        return;
    }
    closing_ = true;
    socket_->flush();
    socket_->close(QWebSocketProtocol::CloseCodeNormal, reason);
}

bool ClientConnection::takeCameraToken() {
    const double seconds = double(cameraClock_.restart()) / 1000.0;
    cameraTokens_ = std::min(kCameraBurst, cameraTokens_ + seconds * kCameraPerSecond);
    if (cameraTokens_ < 1.0) {
        return false;
    }
    cameraTokens_ -= 1.0;
    return true;
}

} // namespace lucent::remote
