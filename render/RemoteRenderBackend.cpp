// RemoteRenderBackend: the connection (open, authenticate, the server's
// messages and refusals, reconnect with growing delays) and its status.
#include "render/RemoteRenderBackend.h"

#include <algorithm>

#include <QNetworkRequest>
#include <QWebSocket>
#include <QWebSocketHandshakeOptions>

#include "protocol/ProtocolMessages.h"
#include "render/RemoteRenderBackend_p.h"

namespace lucent {

namespace {

// Codes after which trying again cannot help (the token, or a client bug).
bool hopeless(const QString& code) {
    return code == "auth-failed" || code == "auth-required" || code == "malformed" ||
           code == "unknown-type" || code == "out-of-order" || code == "too-large";
}

} // namespace

void RemoteRenderBackend::SocketDropper::operator()(QWebSocket* socket) const {
    socket->disconnect();
    socket->deleteLater();
}

RemoteRenderBackend::RemoteRenderBackend(QObject* parent)
    : RenderBackend(parent), offeredVersion_(remote::kProtocolVersion) {
    reconnectTimer_.setSingleShot(true);
    handshakeTimer_.setSingleShot(true);
    cameraTimer_.setSingleShot(true);
    connect(&reconnectTimer_, &QTimer::timeout, this, &RemoteRenderBackend::open);
    connect(&handshakeTimer_, &QTimer::timeout, this, [this] {
        if (socket_) {
            socket_->disconnect(this); // no second report from the abort
            socket_->abort();
        }
        onLost(tr("no answer within %1 s").arg(kHandshakeTimeoutMs / 1000));
    });
    connect(&cameraTimer_, &QTimer::timeout, this, &RemoteRenderBackend::sync);
}

RemoteRenderBackend::~RemoteRenderBackend() {
    if (socket_) {
        socket_->disconnect(this); // no reports from a half-destroyed object
        socket_->abort();
    }
}

void RemoteRenderBackend::setReconnectDelays(int firstMs, int maxMs) {
    firstDelayMs_ = std::max(1, firstMs);
    maxDelayMs_ = std::max(firstDelayMs_, maxMs);
    nextDelayMs_ = firstDelayMs_;
}

QString RemoteRenderBackend::where() const {
    return settings_.url.toDisplayString(QUrl::RemoveUserInfo);
}

void RemoteRenderBackend::setStatus(BackendStatus status, const QString& message) {
    if (status == status_ && message == statusMessage_) {
        return;
    }
    status_ = status;
    statusMessage_ = message;
    emit statusChanged(status_, statusMessage_);
}

void RemoteRenderBackend::connectTo(const RemoteServerSettings& settings) {
    disconnectFromServer();
    settings_ = settings;
    if (const QString problem = settings_.problem(); !problem.isEmpty()) {
        setStatus(BackendStatus::Failed, problem);
        return;
    }
    nextDelayMs_ = firstDelayMs_;
    open();
}

void RemoteRenderBackend::closeConnection() {
    reconnectTimer_.stop();
    handshakeTimer_.stop();
    cameraTimer_.stop();
    phase_ = Phase::Idle;
    openSeries_.clear();
    setSessionId({});
    if (socket_) {
        socket_->abort();
        socket_.reset();
    }
}

void RemoteRenderBackend::disconnectFromServer() {
    closeConnection();
    follow_.reset();
    setFollowState(FollowState::NotFollowing);
    if (status_ != BackendStatus::Failed) {
        setStatus(BackendStatus::Disconnected, tr("not connected"));
    }
}

void RemoteRenderBackend::fail(const QString& message) {
    closeConnection();
    setFollowState(FollowState::NotFollowing);
    setStatus(BackendStatus::Failed, message);
}

void RemoteRenderBackend::open() {
    const bool retry = status_ == BackendStatus::Reconnecting;
    socket_.reset(new QWebSocket(QString(), QWebSocketProtocol::VersionLatest));
    refusal_.clear();
    retryAfterRefusal_ = true;
    wasOpen_ = false;
    seqSent_ = 0; // a new connection: the server counts from 0 again
    firstViewSeq_ = 0;
    serverVersion_ = 0;
    refused_.clear();
    phase_ = Phase::Connecting;
    QWebSocket* s = socket_.get();
    connect(s, &QWebSocket::connected, this, &RemoteRenderBackend::onConnected);
    connect(s, &QWebSocket::textMessageReceived, this, &RemoteRenderBackend::onText);
    connect(s, &QWebSocket::binaryMessageReceived, this, &RemoteRenderBackend::onBinary);
    // A refused connection may report its close before its error: the error says why.
    connect(s, &QWebSocket::disconnected, this, [this, s] {
        onLost(!s->closeReason().isEmpty()                         ? s->closeReason()
               : s->error() != QAbstractSocket::UnknownSocketError ? s->errorString()
                                                                   : tr("closed"));
    });
    // Qt 6.4 names the signal error (errorOccurred from 6.5).
    connect(s, qOverload<QAbstractSocket::SocketError>(&QWebSocket::error), this,
            [this, s](QAbstractSocket::SocketError) { onLost(s->errorString()); });
    setStatus(retry ? BackendStatus::Reconnecting : BackendStatus::Connecting,
              retry ? tr("reconnecting to %1").arg(where()) : tr("connecting to %1").arg(where()));
    handshakeTimer_.start(kHandshakeTimeoutMs);
    // The versions this client speaks, newest first: the server selects the
    // first it speaks, and its hello says which.
    QStringList versions;
    for (int v = offeredVersion_; v >= remote::kOldestProtocolVersion; --v) {
        versions << text(remote::subprotocolName(v));
    }
    if (follow_) {
        setFollowState(FollowState::Joining);
        if (follow_->byInvite()) { // authenticates by itself: hello comes without auth
            versions << "lucent.invite." + follow_->invite;
        }
    }
    QWebSocketHandshakeOptions options;
    options.setSubprotocols(versions);
    s->open(QNetworkRequest(settings_.url), options);
}

void RemoteRenderBackend::onConnected() {
    handshakeTimer_.stop();
    phase_ = Phase::Authenticating;
    if (!follow_ || !follow_->byInvite()) {
        send(remote::writeClientMessage(remote::AuthRequest{settings_.token.toStdString(), {}}));
    }
}

void RemoteRenderBackend::onLost(const QString& why) {
    if (phase_ == Phase::Idle) {
        return;
    }
    handshakeTimer_.stop();
    cameraTimer_.stop();
    phase_ = Phase::Idle;
    openSeries_.clear();
    setSessionId({}); // the server ended it with this connection
    marks_.clear();   // and its marks
    socket_.reset();
    const bool again = retrying_ && (refusal_.isEmpty() || retryAfterRefusal_);
    setFollowState(follow_ && again ? FollowState::Joining : FollowState::NotFollowing);
    if (!refusal_.isEmpty() && !retryAfterRefusal_) {
        setStatus(BackendStatus::Failed, refusal_);
        return;
    }
    const QString reason = refusal_.isEmpty() ? why : refusal_;
    if (!retrying_) {
        setStatus(BackendStatus::Failed,
                  wasOpen_ ? tr("lost the connection to %1 (%2)").arg(where(), reason)
                           : tr("cannot reach %1 (%2)").arg(where(), reason));
        return;
    }
    const QString in = tr("%1 s").arg(nextDelayMs_ / 1000.0, 0, 'g', 2);
    setStatus(
        BackendStatus::Reconnecting,
        wasOpen_ ? tr("lost the connection to %1 (%2); reconnecting in %3").arg(where(), reason, in)
                 : tr("cannot reach %1 (%2); trying again in %3").arg(where(), reason, in));
    reconnectTimer_.start(nextDelayMs_);
    nextDelayMs_ = std::min(2 * nextDelayMs_, maxDelayMs_);
}

void RemoteRenderBackend::send(const std::string& json) {
    if (socket_) {
        socket_->sendTextMessage(text(json));
    }
}

void RemoteRenderBackend::onText(const QString& message) {
    remote::ServerMessage m;
    try {
        m = remote::parseServerMessage(message.toStdString());
    } catch (const remote::ProtocolError& e) {
        if (e.fatal()) {
            emit frameFailed(tr("the server sent a message that cannot be read: %1").arg(e.what()));
        }
        return; // a type this client does not know: a newer server's, skipped
    }
    if (const auto* error = std::get_if<remote::ErrorReply>(&m)) {
        onServerError(text(error->code), text(error->message), error->fatal);
    } else if (follow_ && onFollowMessage(m)) {
        // hello, opened, the session's end, free look: a follower's own way
    } else if (const auto* hello = std::get_if<remote::Hello>(&m);
               hello && phase_ == Phase::Authenticating) {
        serverBackend_ = text(hello->backend);
        serverVersion_ = hello->version;
        phase_ = Phase::Listing;
        if (presenting_) { // the series is opened into the session, de-identified
            send(remote::writeClientMessage(remote::SessionCreate{}));
        }
        send(remote::writeClientMessage(remote::ListRequest{}));
    } else if (const auto* list = std::get_if<remote::SeriesListReply>(&m);
               list && phase_ == Phase::Listing) {
        offered_.clear();
        for (const remote::SeriesSummary& s : list->series) {
            offered_.push_back({text(s.uid), text(s.description), text(s.modality), s.dims});
        }
        chooseSeries();
    } else if (const auto* opened = std::get_if<remote::Opened>(&m);
               opened && phase_ == Phase::Opening) {
        phase_ = Phase::Open;
        wasOpen_ = true;
        openSeries_ = text(opened->series);
        nextDelayMs_ = firstDelayMs_;
        QString note;
        if (volume_ && settings_.series.isEmpty() && opened->dims != volume_->dims()) {
            note = tr("; its volume's size differs from the one loaded here");
        }
        setStatus(BackendStatus::Connected,
                  tr("connected to %1, rendering with %2%3")
                      .arg(where(), serverBackend_.section(',', 0, 0), note));
        sync();
    } else {
        onSessionMessage(m);
    }
}

void RemoteRenderBackend::onServerError(const QString& code, const QString& message, bool fatal) {
    if (fatal) {
        // The server closes the connection after this; onLost reports it.
        retryAfterRefusal_ = !hopeless(code);
        refusal_ = code == "auth-failed" && follow_ && follow_->byInvite()
                       ? tr("%1 refused the invite (%2: %3)").arg(where(), code, message)
                   : code == "auth-failed"
                       ? tr("%1 refused the token (%2: %3)").arg(where(), code, message)
                       : tr("%1 refused (%2: %3)").arg(where(), code, message);
        return;
    }
    if (follow_ && onFollowError(code, message)) {
        return;
    }
    if (isInviteRefusal(code, message)) {
        emit inviteRefused(tr("%1 (%2)").arg(message, code));
    } else if (code == "not-found") {
        fail(tr("%1 has no such series (%2)").arg(where(), message));
    } else if (code == "rate-limited") {
        // The camera was dropped: send it again a little later.
        --seqSent_;
        sent_.erase("camera");
        cameraTimer_.start(kCameraIntervalMs);
    } else if (code == "bad-request") {
        // Not counted by the server, and not shown: until a new value of its
        // kind ("camera: ...") goes out, no frame shows the view wanted.
        --seqSent_;
        const qsizetype colon = message.indexOf(':');
        refused_.insert(colon > 0 && !message.left(colon).contains(' ') ? message.left(colon)
                                                                        : QString());
        emit frameFailed(tr("the server refused a request: %1").arg(message));
    } else {
        emit frameFailed(tr("the server could not render (%1): %2").arg(code, message));
    }
}

} // namespace lucent
