#include "server/ClientConnection.h"

#include <QLoggingCategory>

#include <nlohmann/json.hpp>

#include "server/RenderServer.h"

namespace lucent::remote {
namespace {

Q_LOGGING_CATEGORY(lcClient, "lucent.server.client")

// A new render waits while this much of the previous frame is still unsent.
constexpr qint64 kMaxUnsentBytes = 0;

std::string defaultPreset(const SeriesEntry& series, RenderMode mode) {
    if (series.modality != "CT") {
        return "mr-default";
    }
    return mode == RenderMode::Dvr ? "ct-bone" : "ct-mip";
}

} // namespace

ClientConnection::ClientConnection(quint64 id, QWebSocket* socket, RenderServer& server)
    : QObject(&server), id_(id), socket_(socket), server_(server) {
    socket->setParent(this);
    // Qt closes the connection itself beyond this; below it the protocol's
    // own limit answers with an error message first.
    socket->setMaxAllowedIncomingMessageSize(4 * kMaxMessageBytes);
    connect(socket, &QWebSocket::textMessageReceived, this, &ClientConnection::onText);
    connect(socket, &QWebSocket::binaryMessageReceived, this, &ClientConnection::onBinary);
    connect(socket, &QWebSocket::bytesWritten, this, &ClientConnection::pump);
    connect(socket, &QWebSocket::disconnected, this, [this] {
        qCInfo(lcClient) << "client" << id_ << "disconnected";
        emit closed(id_);
    });
    authTimer_.setSingleShot(true);
    connect(&authTimer_, &QTimer::timeout, this,
            [this] { sendError("auth-timeout", "no auth message within the time allowed", true); });
    authTimer_.start(kAuthTimeoutMs);
    cameraClock_.start();
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
        socket_->close(QWebSocketProtocol::CloseCodePolicyViolated, QString::fromStdString(code));
    }
}

void ClientConnection::onBinary(const QByteArray&) {
    sendError("malformed", "binary messages are not part of the client's protocol", true);
}

void ClientConnection::onText(const QString& text) {
    if (closing_) {
        return;
    }
    const QByteArray utf8 = text.toUtf8();
    try {
        handle(parseClientMessage(std::string_view(utf8.constData(), std::size_t(utf8.size()))));
    } catch (const ProtocolError& e) {
        sendError(e.code(), e.what(), e.fatal());
    }
}

void ClientConnection::handle(const ClientMessage& message) {
    if (!authenticated_) {
        const auto* auth = std::get_if<AuthRequest>(&message);
        if (!auth) {
            sendError("auth-required",
                      "the first message must be {\"type\":\"auth\",\"token\":...}", true);
        } else if (!server_.acceptsToken(auth->token)) {
            sendError("auth-failed", "the token is not valid", true);
        } else {
            authenticated_ = true;
            authTimer_.stop();
            qCInfo(lcClient) << "client" << id_ << "authenticated";
            sendJson(nlohmann::json{{"type", "hello"},
                                    {"version", kProtocolVersion},
                                    {"backend", server_.backendDescription().toStdString()}}
                         .dump());
        }
        return;
    }
    if (std::holds_alternative<AuthRequest>(message)) {
        sendError("out-of-order", "already authenticated", true);
    } else if (std::holds_alternative<ListRequest>(message)) {
        nlohmann::json list = nlohmann::json::array();
        for (const auto& s : server_.series()) {
            const glm::ivec3 d = s->geometry.dims;
            list.push_back({{"uid", s->id},
                            {"description", s->description},
                            {"modality", s->modality},
                            {"dims", {d.x, d.y, d.z}}});
        }
        sendJson(nlohmann::json{{"type", "series"}, {"series", list}}.dump());
    } else if (const auto* open = std::get_if<OpenRequest>(&message)) {
        auto series = server_.findSeries(open->series);
        if (!series) {
            sendError("not-found", "no series with uid '" + open->series.substr(0, 128) + "'",
                      false);
            return;
        }
        const int width = description_.width, height = description_.height;
        series_ = std::move(series);
        description_ = RenderDescription{};
        description_.width = width;
        description_.height = height;
        const std::string preset = defaultPreset(*series_, description_.mode);
        description_.transferFunction = loadPreset(preset);
        qCInfo(lcClient) << "client" << id_ << "opened a series";
        const glm::ivec3 d = series_->geometry.dims;
        sendJson(nlohmann::json{
            {"type", "opened"},
            {"series", series_->id},
            {"dims", {d.x, d.y, d.z}},
            {"preset",
             preset}}.dump());
        changed();
    } else if (!series_) {
        sendError("out-of-order", "open a series first", true);
    } else {
        handleView(message);
    }
}

void ClientConnection::handleView(const ClientMessage& message) {
    if (const auto* camera = std::get_if<CameraUpdate>(&message)) {
        if (!takeCameraToken()) {
            sendError("rate-limited", "too many camera updates; this one was dropped", false);
            return;
        }
        Camera& c = description_.camera;
        c.azimuth = camera->azimuth.value_or(c.azimuth);
        c.elevation = camera->elevation.value_or(c.elevation);
        c.zoom = camera->zoom.value_or(c.zoom);
    } else if (const auto* tf = std::get_if<TransferFunctionUpdate>(&message)) {
        try {
            description_.transferFunction =
                tf->preset ? loadPreset(*tf->preset) : *tf->transferFunction;
        } catch (const TransferFunctionError& e) {
            sendError("bad-request", e.what(), false);
            return;
        }
    } else if (const auto* mode = std::get_if<ModeUpdate>(&message)) {
        description_.mode = mode->mode;
        description_.isoValue = mode->isoValue.value_or(description_.isoValue);
    } else if (const auto* clip = std::get_if<ClipUpdate>(&message)) {
        description_.clip = clip->box;
    } else if (const auto* quality = std::get_if<QualityUpdate>(&message)) {
        quality_ = quality->quality;
    } else if (const auto* size = std::get_if<SizeUpdate>(&message)) {
        description_.width = size->width;
        description_.height = size->height;
    }
    // RenderRequest: nothing changes but a frame is owed.
    changed();
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

void ClientConnection::changed() {
    ++seq_;
    renderWanted_ = true;
    pump();
}

void ClientConnection::pump() {
    if (!socket_ || closing_ || !renderWanted_ || renderInFlight_ || !series_ ||
        socket_->bytesToWrite() > kMaxUnsentBytes) {
        return;
    }
    renderWanted_ = false;
    renderInFlight_ = true;
    server_.submit(RenderJob{id_, series_, description_, quality_, seq_});
}

void ClientConnection::deliver(const RenderedFrame& frame) {
    renderInFlight_ = false;
    if (!socket_ || closing_) {
        return;
    }
    if (!frame.error.isEmpty()) {
        sendError("render-failed", frame.error.toStdString(), false);
    } else {
        socket_->sendBinaryMessage(frame.message);
    }
    pump();
}

} // namespace lucent::remote
