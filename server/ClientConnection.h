#pragma once
// One WebSocket client of the render server: authentication, the state of its
// view, and the frames it is owed. At most one frame per client is being
// rendered and at most one is being written; changes that arrive meanwhile
// are coalesced into the next render, so a client never gets stale frames
// queued behind newer ones.

#include <QElapsedTimer>
#include <QObject>
#include <QPointer>
#include <QTimer>
#include <QWebSocket>

#include <cstdint>
#include <memory>

#include "core/io/SeriesEntry.h"
#include "core/raycast/RenderDescription.h"
#include "server/RenderWorker.h"
#include "server/protocol/ProtocolMessages.h"

namespace lucent::remote {

class RenderServer;

// Camera updates: a burst of this many, then this many per second.
inline constexpr double kCameraBurst = 60.0;
inline constexpr double kCameraPerSecond = 60.0;
// A client must authenticate within this time.
inline constexpr int kAuthTimeoutMs = 10000;

class ClientConnection : public QObject {
    Q_OBJECT
public:
    // Takes the socket (as a Qt child).
    ClientConnection(quint64 id, QWebSocket* socket, RenderServer& server);

    quint64 id() const { return id_; }
    // A frame the render thread finished for this client.
    void deliver(const RenderedFrame& frame);
    // Sends an error; a fatal one closes the connection after it.
    void sendError(const std::string& code, const std::string& message, bool fatal);

signals:
    void closed(quint64 id);

private:
    void onText(const QString& text);
    void onBinary(const QByteArray& data);
    void handle(const ClientMessage& message);
    void handleView(const ClientMessage& message);
    void sendJson(const std::string& json);
    bool takeCameraToken();
    void changed();
    void pump();

    quint64 id_;
    QPointer<QWebSocket> socket_;
    RenderServer& server_;
    QTimer authTimer_;
    bool authenticated_ = false;
    bool closing_ = false;

    std::shared_ptr<const SeriesEntry> series_;
    RenderDescription description_; // volume stays null: the render thread fills it in
    Quality quality_ = Quality::Still;
    std::uint64_t seq_ = 0; // accepted view changes so far
    bool renderInFlight_ = false;
    bool renderWanted_ = false;

    double cameraTokens_ = kCameraBurst;
    QElapsedTimer cameraClock_;
};

} // namespace lucent::remote
