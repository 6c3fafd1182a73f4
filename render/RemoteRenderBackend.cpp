#include "render/RemoteRenderBackend.h"

#include <algorithm>

#include <QImage>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QWebSocket>

#include "protocol/ProtocolMessages.h"

namespace lucent {

namespace {

constexpr int kMinSide = 16;

bool sameCamera(const Camera& a, const Camera& b) {
    return a.azimuth == b.azimuth && a.elevation == b.elevation && a.zoom == b.zoom &&
           a.distance == b.distance && a.panRight == b.panRight && a.panUp == b.panUp;
}

bool movedFromTheCentre(const Camera& c) {
    return c.distance != 0.0 || c.panRight != 0.0 || c.panUp != 0.0;
}

bool sameClip(const ClipBox& a, const ClipBox& b) {
    return a.lo == b.lo && a.hi == b.hi;
}

bool clipsNothing(const ClipBox& clip) {
    return sameClip(clip, ClipBox{});
}

QJsonArray vector3(const glm::dvec3& v) {
    return {v.x, v.y, v.z};
}

std::pair<RenderMode, double> modeOf(const RenderDescription& d) {
    // The iso value matters only to isosurfaces.
    return {d.mode, d.mode == RenderMode::Isosurface ? d.isoValue : 0.0};
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

} // namespace

void RemoteRenderBackend::SocketDropper::operator()(QWebSocket* socket) const {
    socket->disconnect();
    socket->deleteLater();
}

RemoteRenderBackend::RemoteRenderBackend(QObject* parent) : RenderBackend(parent) {
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
    if (socket_) {
        socket_->abort();
        socket_.reset();
    }
}

void RemoteRenderBackend::disconnectFromServer() {
    closeConnection();
    if (status_ != BackendStatus::Failed) {
        setStatus(BackendStatus::Disconnected, tr("not connected"));
    }
}

void RemoteRenderBackend::fail(const QString& message) {
    closeConnection();
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
    refused_.clear();
    phase_ = Phase::Connecting;
    QWebSocket* s = socket_.get();
    connect(s, &QWebSocket::connected, this, &RemoteRenderBackend::onConnected);
    connect(s, &QWebSocket::textMessageReceived, this, &RemoteRenderBackend::onText);
    connect(s, &QWebSocket::binaryMessageReceived, this, &RemoteRenderBackend::onBinary);
    connect(s, &QWebSocket::disconnected, this,
            [this, s] { onLost(s->closeReason().isEmpty() ? tr("closed") : s->closeReason()); });
    // Qt 6.4 names the signal error (errorOccurred from 6.5).
    connect(s, qOverload<QAbstractSocket::SocketError>(&QWebSocket::error), this,
            [this, s](QAbstractSocket::SocketError) { onLost(s->errorString()); });
    setStatus(retry ? BackendStatus::Reconnecting : BackendStatus::Connecting,
              retry ? tr("reconnecting to %1").arg(where()) : tr("connecting to %1").arg(where()));
    handshakeTimer_.start(kHandshakeTimeoutMs);
    s->open(settings_.url);
}

void RemoteRenderBackend::onConnected() {
    handshakeTimer_.stop();
    phase_ = Phase::Authenticating;
    sendJson({{"type", "auth"}, {"token", settings_.token}});
}

void RemoteRenderBackend::onLost(const QString& why) {
    if (phase_ == Phase::Idle) {
        return;
    }
    handshakeTimer_.stop();
    cameraTimer_.stop();
    phase_ = Phase::Idle;
    openSeries_.clear();
    socket_.reset();
    if (!refusal_.isEmpty() && !retryAfterRefusal_) {
        setStatus(BackendStatus::Failed, refusal_);
        return;
    }
    const QString reason = refusal_.isEmpty() ? why : refusal_;
    const QString in = tr("%1 s").arg(nextDelayMs_ / 1000.0, 0, 'g', 2);
    setStatus(
        BackendStatus::Reconnecting,
        wasOpen_ ? tr("lost the connection to %1 (%2); reconnecting in %3").arg(where(), reason, in)
                 : tr("cannot reach %1 (%2); trying again in %3").arg(where(), reason, in));
    reconnectTimer_.start(nextDelayMs_);
    nextDelayMs_ = std::min(2 * nextDelayMs_, maxDelayMs_);
}

void RemoteRenderBackend::sendJson(const QJsonObject& message) {
    if (socket_) {
        socket_->sendTextMessage(
            QString::fromUtf8(QJsonDocument(message).toJson(QJsonDocument::Compact)));
    }
}

void RemoteRenderBackend::sendView(const QJsonObject& message) {
    sendJson(message);
    ++seqSent_;
    // A new value of a refused kind may be accepted (an unnamed refusal: any).
    refused_.remove(message["type"].toString());
    refused_.remove(QString());
}

void RemoteRenderBackend::onText(const QString& text) {
    const QJsonObject m = QJsonDocument::fromJson(text.toUtf8()).object();
    const QString type = m["type"].toString();
    if (type == "error") {
        onServerError(m["code"].toString(), m["message"].toString(), m["fatal"].toBool());
    } else if (type == "hello" && phase_ == Phase::Authenticating) {
        serverBackend_ = m["backend"].toString();
        phase_ = Phase::Listing;
        sendJson({{"type", "list"}});
    } else if (type == "series" && phase_ == Phase::Listing) {
        chooseSeries(m["series"].toArray());
    } else if (type == "opened" && phase_ == Phase::Opening) {
        phase_ = Phase::Open;
        wasOpen_ = true;
        openSeries_ = m["series"].toString();
        nextDelayMs_ = firstDelayMs_;
        QString note;
        const QJsonArray dims = m["dims"].toArray();
        if (volume_ && settings_.series.isEmpty() &&
            (dims.size() != 3 || dims[0].toInt() != volume_->dims().x ||
             dims[1].toInt() != volume_->dims().y || dims[2].toInt() != volume_->dims().z)) {
            note = tr("; its volume's size differs from the one loaded here");
        }
        setStatus(BackendStatus::Connected,
                  tr("connected to %1, rendering with %2%3")
                      .arg(where(), serverBackend_.section(',', 0, 0), note));
        sync();
    }
}

void RemoteRenderBackend::onServerError(const QString& code, const QString& message, bool fatal) {
    if (fatal) {
        // The server closes the connection after this; onLost reports it.
        retryAfterRefusal_ = !hopeless(code);
        refusal_ = code == "auth-failed"
                       ? tr("%1 refused the token (%2: %3)").arg(where(), code, message)
                       : tr("%1 refused (%2: %3)").arg(where(), code, message);
        return;
    }
    if (code == "not-found") {
        fail(tr("%1 has no such series (%2)").arg(where(), message));
    } else if (code == "rate-limited") {
        // The camera was dropped: send it again a little later.
        --seqSent_;
        sent_.camera.reset();
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

void RemoteRenderBackend::chooseSeries(const QJsonArray& offered) {
    const QString wanted = !settings_.series.isEmpty() ? settings_.series
                           : volume_                   ? QString::fromStdString(volume_->seriesUid)
                                                       : QString();
    if (wanted.isEmpty()) {
        fail(tr("no volume is loaded and the settings name no series"));
        return;
    }
    offered_.clear();
    for (const QJsonValue& entry : offered) {
        const QJsonObject s = entry.toObject();
        const QJsonArray d = s["dims"].toArray();
        offered_.push_back({s["uid"].toString(), s["description"].toString(),
                            s["modality"].toString(),
                            glm::ivec3(d.at(0).toInt(), d.at(1).toInt(), d.at(2).toInt())});
    }
    // The server names further parts of one UID "UID#n": the one of our size.
    QString chosen;
    for (const QJsonValue& entry : offered) {
        const QJsonObject s = entry.toObject();
        const QString uid = s["uid"].toString();
        if (uid == wanted) {
            chosen = uid;
            break;
        }
        const QJsonArray d = s["dims"].toArray();
        if (chosen.isEmpty() && uid.startsWith(wanted + "#") && volume_ && d.size() == 3 &&
            d[0].toInt() == volume_->dims().x && d[1].toInt() == volume_->dims().y &&
            d[2].toInt() == volume_->dims().z) {
            chosen = uid;
        }
    }
    if (chosen.isEmpty()) {
        fail(tr("%1 does not have series %2 (it offers %3 series)")
                 .arg(where(), wanted)
                 .arg(offered.size()));
        return;
    }
    phase_ = Phase::Opening;
    sent_ = ViewParts{};
    refused_.clear(); // everything goes out again
    // The server counts view messages per connection, across re-opens: the
    // count goes on, and frames of the series before are older than the new
    // view's first (firstViewSeq_, set by the first sync).
    firstViewSeq_ = 0;
    sendView({{"type", "open"}, {"series", chosen}});
}

void RemoteRenderBackend::setVolume(std::shared_ptr<const Volume> volume) {
    volume_ = std::move(volume);
    wanted_.reset();
    if (phase_ == Phase::Open || phase_ == Phase::Opening || phase_ == Phase::Listing) {
        // Open the new volume's series (or the one the settings name) again.
        phase_ = Phase::Listing;
        cameraTimer_.stop();
        sendJson({{"type", "list"}});
    }
}

void RemoteRenderBackend::request(const RenderDescription& still, const FrameOptions& options) {
    wanted_ = WantedView{still, options.interactive};
    sync();
}

void RemoteRenderBackend::sync() {
    if (phase_ != Phase::Open || !wanted_ || cameraTimer_.isActive()) {
        return;
    }
    const RenderDescription& d = wanted_->still;
    // Camera messages are paced; the rest waits with them so that a still
    // frame never shows an old camera.
    if (sent_.camera && !sameCamera(*sent_.camera, d.camera) && cameraClock_.isValid() &&
        cameraClock_.elapsed() < kCameraIntervalMs) {
        cameraTimer_.start(int(kCameraIntervalMs - cameraClock_.elapsed()));
        return;
    }
    // A drag is an interaction: adaptive JPEG frames until its end, which owes
    // one lossless still (after `open` the server is not interacting). The
    // start goes before the changes and the end after them, so that no still
    // is rendered for a half-way camera.
    const bool interacting = sent_.interactive.value_or(false);
    if (wanted_->interactive && !interacting) {
        sendView({{"type", "interaction"}, {"state", "start"}});
    }
    sent_.interactive = wanted_->interactive;
    const QSize size(std::clamp(d.width, kMinSide, remote::kMaxImageSide),
                     std::clamp(d.height, kMinSide, remote::kMaxImageSide));
    if (sent_.size != size) {
        sendView({{"type", "size"}, {"width", size.width()}, {"height", size.height()}});
        sent_.size = size;
    }
    if (sent_.transferFunction != d.transferFunction) {
        const QJsonObject tf =
            QJsonDocument::fromJson(QByteArray::fromStdString(toJson(d.transferFunction))).object();
        sendView({{"type", "tf"}, {"tf", tf}});
        sent_.transferFunction = d.transferFunction;
    }
    if (sent_.mode != modeOf(d)) {
        QJsonObject mode{{"type", "mode"}, {"mode", renderModeName(d.mode)}};
        if (d.mode == RenderMode::Isosurface) {
            mode["iso"] = d.isoValue;
        }
        sendView(mode);
        sent_.mode = modeOf(d);
    }
    if (!sent_.clip || !sameClip(*sent_.clip, d.clip)) {
        QJsonObject clip{{"type", "clip"}};
        if (!clipsNothing(d.clip)) {
            clip["lo"] = vector3(d.clip.lo);
            clip["hi"] = vector3(d.clip.hi);
        }
        sendView(clip);
        sent_.clip = d.clip;
    }
    if (!sent_.camera || !sameCamera(*sent_.camera, d.camera)) {
        QJsonObject camera{{"type", "camera"},
                           {"azimuth", d.camera.azimuth},
                           {"elevation", d.camera.elevation},
                           {"zoom", d.camera.zoom}};
        // Sent once the view has left the orbit about the centre: a server older
        // than these fields refuses them, and to it nothing else is lost.
        if (movedFromTheCentre(d.camera) || (sent_.camera && movedFromTheCentre(*sent_.camera))) {
            camera["distance"] = d.camera.distance;
            camera["pan_right"] = d.camera.panRight;
            camera["pan_up"] = d.camera.panUp;
        }
        sendView(camera);
        sent_.camera = d.camera;
        cameraClock_.start();
    }
    if (!wanted_->interactive && interacting) {
        sendView({{"type", "interaction"}, {"state", "end"}});
    }
    if (firstViewSeq_ == 0) {
        firstViewSeq_ = seqSent_;
    }
}

void RemoteRenderBackend::onBinary(const QByteArray& message) {
    try {
        const auto frame = remote::parseFrameMessage(
            std::string_view(message.constData(), std::size_t(message.size())));
        if (phase_ != Phase::Open || firstViewSeq_ == 0 || frame.header.seq < firstViewSeq_) {
            return; // the server's defaults, or a series no longer wanted
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
        out.current =
            frame.header.seq == seqSent_ && !cameraTimer_.isActive() && refused_.isEmpty();
        out.renderMs = frame.header.renderMs;
        out.jpegQuality = frame.header.format == "jpeg" ? frame.header.jpegQuality : 0;
        out.scale = frame.header.scale;
        emit frameReady(out);
    } catch (const std::exception& e) {
        emit frameFailed(tr("a frame from the server cannot be read: %1").arg(e.what()));
    }
}

} // namespace lucent
