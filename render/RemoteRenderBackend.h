#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <QElapsedTimer>
#include <QSet>
#include <QSize>
#include <QTimer>

#include "render/RemoteServerSettings.h"
#include "render/RenderBackend.h"

class QJsonArray;
class QJsonObject;
class QWebSocket;

namespace lucent {

// A series a server offers (its `series` reply).
struct OfferedSeries {
    QString uid; // what `open` takes
    QString description;
    QString modality;
    glm::ivec3 dims{0};
};

// A lucent-server client (docs/protocol.md, v1) behind RenderBackend:
// authenticates, lists the server's series and opens the one matching the
// loaded volume (or the one the settings name), sends only the parts of the
// view that changed (size, transfer function, mode, clip box, camera; a drag
// as interaction start/end, so the server adapts its JPEG frames to hold the
// frame rate), decodes the PNG (still) and JPEG (interactive) frames, tells
// from their `seq` whether they show the newest request. A lost connection is
// reopened by itself with growing delays and the whole view sent again; the
// status says connecting, connected, reconnecting or failed (with the
// server's refusal: a wrong token, a series it does not have).
//
// The protocol carries azimuth, elevation and zoom of the camera; the view's
// other camera fields and the sampling settings are the server's defaults.
class RemoteRenderBackend : public RenderBackend {
    Q_OBJECT

public:
    // Camera messages at most this often (the server drops more than 60 a second).
    static constexpr int kCameraIntervalMs = 20;
    // A connection attempt that has not opened after this long is given up (and retried).
    static constexpr int kHandshakeTimeoutMs = 10000;

    explicit RemoteRenderBackend(QObject* parent = nullptr);
    ~RemoteRenderBackend() override;

    // Connects (again) with these settings; the view requested so far is sent
    // once the series is open. Bad settings fail at once, naming the field.
    void connectTo(const RemoteServerSettings& settings);
    void disconnectFromServer();
    const RemoteServerSettings& settings() const { return settings_; }

    void setVolume(std::shared_ptr<const Volume> volume) override;
    void request(const RenderDescription& still, const FrameOptions& options) override;
    BackendStatus status() const override { return status_; }
    QString statusMessage() const { return statusMessage_; }

    // From the server's hello: what it renders with ("cpu", "gl: ...").
    QString serverBackend() const { return serverBackend_; }
    // The id of the series open on the server; empty before.
    QString openSeries() const { return openSeries_; }
    // What the server offered in its last `series` reply (kept after a failure,
    // so that the user can pick one).
    const std::vector<OfferedSeries>& offeredSeries() const { return offered_; }
    // View messages the server has accepted or owes a frame for on this connection.
    std::uint64_t sentSeq() const { return seqSent_; }

    // The first retry after firstMs, each next one twice as late, at most maxMs.
    void setReconnectDelays(int firstMs, int maxMs);

private:
    enum class Phase { Idle, Connecting, Authenticating, Listing, Opening, Open };
    // What the server has been told, part by part; nullopt: not yet (sent whole).
    struct ViewParts {
        std::optional<Camera> camera;
        std::optional<TransferFunction> transferFunction;
        std::optional<std::pair<RenderMode, double>> mode;
        std::optional<ClipBox> clip;
        std::optional<QSize> size;
        std::optional<bool> interactive;
    };
    struct WantedView {
        RenderDescription still;
        bool interactive = false;
    };

    void open();
    void onConnected();
    void onText(const QString& text);
    void onBinary(const QByteArray& message);
    void onLost(const QString& why);
    void onServerError(const QString& code, const QString& message, bool fatal);
    void chooseSeries(const QJsonArray& offered);
    void sync();
    void sendJson(const QJsonObject& message);
    void sendView(const QJsonObject& message);
    // Stops the timers and drops the socket (no status change).
    void closeConnection();
    void fail(const QString& message);
    void setStatus(BackendStatus status, const QString& message);
    QString where() const;

    // Disconnects its signals and deletes it later: a socket may be dropped
    // from inside one of its own signals.
    struct SocketDropper {
        void operator()(QWebSocket* socket) const;
    };

    RemoteServerSettings settings_;
    std::unique_ptr<QWebSocket, SocketDropper> socket_;
    Phase phase_ = Phase::Idle;
    BackendStatus status_ = BackendStatus::Disconnected;
    QString statusMessage_;
    QString serverBackend_;
    QString openSeries_;
    std::vector<OfferedSeries> offered_;
    QString refusal_; // a fatal refusal, reported when the server closes
    bool retryAfterRefusal_ = true;
    bool wasOpen_ = false; // this connection got as far as an open series

    std::shared_ptr<const Volume> volume_;
    std::optional<WantedView> wanted_;
    ViewParts sent_;
    std::uint64_t seqSent_ = 0;
    std::uint64_t firstViewSeq_ = 0; // frames before this show the server's defaults
    // Kinds of view message the server refused ("camera", ...; "" when it did
    // not say), each until a new value of that kind is sent.
    QSet<QString> refused_;

    QTimer reconnectTimer_;
    QTimer handshakeTimer_;
    QTimer cameraTimer_;
    QElapsedTimer cameraClock_;
    int firstDelayMs_ = 500;
    int maxDelayMs_ = 8000;
    int nextDelayMs_ = 500;
};

} // namespace lucent
