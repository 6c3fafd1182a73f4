#include "render/RemoteRenderBackend.h"

#include <algorithm>

#include <QImage>
#include <QNetworkRequest>
#include <QWebSocket>
#include <QWebSocketHandshakeOptions>

#include "protocol/ProtocolMessages.h"

namespace lucent {

namespace {

// Camera keys that servers of version 1 before its camera distance and pan refuse.
constexpr std::string_view kCentreKeys[] = {"distance", "pan_right", "pan_up"};

bool offCentre(const remote::CameraUpdate& camera) {
    return std::any_of(std::begin(kCentreKeys), std::end(kCentreKeys), [&](std::string_view key) {
        return camera.number(key).value_or(0.0) != 0.0;
    });
}

ImageRGBA8 toImage(const QImage& decoded) {
    const QImage q = decoded.convertToFormat(QImage::Format_RGBA8888);
    ImageRGBA8 out = ImageRGBA8::filled(q.width(), q.height());
    for (int y = 0; y < q.height(); ++y) {
        std::copy_n(q.constScanLine(y), 4 * q.width(), out.at(0, y));
    }
    return out;
}

// Codes after which trying again cannot help (the token, or a client bug).
bool hopeless(const QString& code) {
    return code == "auth-failed" || code == "auth-required" || code == "malformed" ||
           code == "unknown-type" || code == "out-of-order" || code == "too-large";
}

QString text(const std::string& s) {
    return QString::fromStdString(s);
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

void RemoteRenderBackend::sendView(const std::string& type, const std::string& json) {
    send(json);
    ++seqSent_;
    // A new value of a refused kind may be accepted (an unnamed refusal: any).
    refused_.remove(text(type));
    refused_.remove(QString());
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

void RemoteRenderBackend::chooseSeries() {
    const QString wanted = !settings_.series.isEmpty() ? settings_.series
                           : volume_                   ? QString::fromStdString(volume_->seriesUid)
                                                       : QString();
    if (wanted.isEmpty()) {
        fail(tr("no volume is loaded and the settings name no series"));
        return;
    }
    // The server names further parts of one UID "UID#n": the one of our size.
    QString chosen;
    for (const OfferedSeries& s : offered_) {
        if (s.uid == wanted) {
            chosen = s.uid;
            break;
        }
        if (chosen.isEmpty() && s.uid.startsWith(wanted + "#") && volume_ &&
            s.dims == volume_->dims()) {
            chosen = s.uid;
        }
    }
    if (chosen.isEmpty()) {
        fail(tr("%1 does not have series %2 (it offers %3 series)")
                 .arg(where(), wanted)
                 .arg(offered_.size()));
        return;
    }
    phase_ = Phase::Opening;
    sent_.clear(); // everything goes out again
    interacting_ = false;
    sentOffCentre_ = false;
    refused_.clear();
    // The server counts view messages per connection, across re-opens: the
    // count goes on, and frames of the series before are older than the new
    // view's first (firstViewSeq_, set by the first sync).
    firstViewSeq_ = 0;
    sendView("open", remote::writeClientMessage(remote::OpenRequest{chosen.toStdString()}));
}

void RemoteRenderBackend::setVolume(std::shared_ptr<const Volume> volume) {
    volume_ = std::move(volume);
    wanted_.reset();
    if (!follow_ &&
        (phase_ == Phase::Open || phase_ == Phase::Opening || phase_ == Phase::Listing)) {
        // Open the new volume's series (or the one the settings name) again.
        phase_ = Phase::Listing;
        cameraTimer_.stop();
        send(remote::writeClientMessage(remote::ListRequest{}));
    }
}

void RemoteRenderBackend::request(const RenderDescription& still, const FrameOptions& options) {
    wanted_ = WantedView{still, options.interactive};
    sync();
}

void RemoteRenderBackend::sync() {
    if (phase_ != Phase::Open || !wanted_ || cameraTimer_.isActive() ||
        (follow_ && followState_ != FollowState::LookingAround)) {
        return;
    }
    const RenderDescription& d = wanted_->still;
    std::vector<remote::ClientMessage> messages = remote::viewMessages(d);
    if (follow_) { // in free look the session's transfer function, mode and clip box stay
        std::erase_if(messages, [](const remote::ClientMessage& m) {
            return !std::holds_alternative<remote::CameraUpdate>(m) &&
                   !std::holds_alternative<remote::SizeUpdate>(m);
        });
    }
    for (remote::ClientMessage& m : messages) {
        auto* camera = std::get_if<remote::CameraUpdate>(&m);
        // A version 1 server before camera distance and pan refuses those keys:
        // they go once the view has left the orbit about the centre, and to such a
        // server nothing else is lost.
        if (camera && serverVersion_ < 2 && !offCentre(*camera) && !sentOffCentre_) {
            std::erase_if(camera->values, [](const remote::OptionValue& v) {
                return std::find(std::begin(kCentreKeys), std::end(kCentreKeys),
                                 v.option->wireKey) != std::end(kCentreKeys);
            });
        }
        // Camera messages are paced; the rest waits with them so that a still
        // frame never shows an old camera.
        if (camera && sent_.count("camera") && sent_["camera"] != remote::writeClientMessage(m) &&
            cameraClock_.isValid() && cameraClock_.elapsed() < kCameraIntervalMs) {
            cameraTimer_.start(int(kCameraIntervalMs - cameraClock_.elapsed()));
            return;
        }
    }
    // A drag is an interaction: adaptive JPEG frames until its end, which owes
    // one lossless still (after `open` the server is not interacting). The
    // start goes before the changes and the end after them, so that no still
    // is rendered for a half-way camera.
    const bool interacting = interacting_;
    if (wanted_->interactive && !interacting) {
        sendView("interaction", remote::writeClientMessage(remote::InteractionUpdate{true}));
    }
    interacting_ = wanted_->interactive;
    for (const remote::ClientMessage& m : messages) {
        const std::string type(remote::messageType(m));
        const std::string json = remote::writeClientMessage(m);
        if (const auto it = sent_.find(type); it != sent_.end() && it->second == json) {
            continue;
        }
        sent_[type] = json;
        if (remote::messageVersion(m) > serverVersion_) {
            refuseNewerMessage(type, json, d);
            continue;
        }
        sendView(type, json);
        if (const auto* camera = std::get_if<remote::CameraUpdate>(&m)) {
            sentOffCentre_ = sentOffCentre_ || offCentre(*camera);
            cameraClock_.start();
        }
    }
    if (!wanted_->interactive && interacting) {
        sendView("interaction", remote::writeClientMessage(remote::InteractionUpdate{false}));
    }
    if (firstViewSeq_ == 0) {
        firstViewSeq_ = seqSent_;
    }
}

void RemoteRenderBackend::refuseNewerMessage(const std::string& type, const std::string& json,
                                             const RenderDescription& wanted) {
    // Only sampling is newer than version 1. The server renders with the
    // sampling a description has by default (shading: the transfer function's):
    // a view that asks for that loses nothing.
    RenderDescription server;
    server.transferFunction = wanted.transferFunction;
    const remote::SamplingUpdate theirs{remote::optionUpdate(kWireSampling, server)};
    if (type != "sampling" || json == remote::writeClientMessage(theirs)) {
        if (refused_.remove(text(type))) {
            // The frames since the refusal show the view wanted now: one more says so.
            sendView("render", remote::writeClientMessage(remote::RenderRequest{}));
        }
        return;
    }
    QStringList settings;
    for (const remote::OptionValue& v : remote::optionUpdate(kWireSampling, wanted).values) {
        if (theirs.text(v.option->wireKey) != v.text) {
            settings << QString::fromUtf8(v.option->name.data(), qsizetype(v.option->name.size())) +
                            " " + text(v.text);
        }
    }
    refused_.insert(text(type));
    emit frameFailed(tr("%1 speaks protocol version %2, which cannot carry the sampling settings "
                        "(%3): it renders with its own (sampling needs version %4)")
                         .arg(where())
                         .arg(serverVersion_)
                         .arg(settings.join(", "))
                         .arg(remote::messageTypeVersion(type)));
}

void RemoteRenderBackend::onBinary(const QByteArray& message) {
    try {
        const auto frame = remote::parseFrameMessage(
            std::string_view(message.constData(), std::size_t(message.size())));
        // A follower shows every frame of the session; its own view's (free look) from
        // free-look-started on.
        const bool ownView = !follow_ || followState_ == FollowState::LookingAround;
        if (phase_ != Phase::Open || frame.header.slice ||
            (ownView && (firstViewSeq_ == 0 || frame.header.seq < firstViewSeq_))) {
            return; // the server's defaults, a series no longer wanted, or an MPR slice (v4)
        }
        QImage decoded;
        const char* format = frame.header.format == "png" ? "PNG" : "JPEG";
        if (!decoded.loadFromData(reinterpret_cast<const uchar*>(frame.image.data()),
                                  int(frame.image.size()), format)) {
            emit frameFailed(tr("a %1 frame from the server cannot be decoded").arg(format));
            return;
        }
        BackendFrame out;
        out.image = toImage(decoded);
        out.interactive = frame.header.quality == remote::Quality::Interactive;
        // Not the view the user wants while a paced camera waits for its timer
        // or a refused change has not been replaced.
        out.current = !ownView || (frame.header.seq == seqSent_ && !cameraTimer_.isActive() &&
                                   refused_.isEmpty());
        out.renderMs = frame.header.renderMs;
        out.jpegQuality = frame.header.format == "jpeg" ? frame.header.jpegQuality : 0;
        out.scale = frame.header.scale;
        out.projection = frame.header.projection;
        emit frameReady(out);
    } catch (const std::exception& e) {
        emit frameFailed(tr("a frame from the server cannot be read: %1").arg(e.what()));
    }
}

} // namespace lucent
