#pragma once
// lucent-server's core: a WebSocket server (protocol v1, docs/protocol.md)
// that authenticates clients with tokens, lists the series it holds, and
// renders each client's view on one render thread.

#include <QHash>
#include <QHostAddress>
#include <QObject>
#include <QPointer>
#include <QThread>
#include <QWebSocketServer>

#include <memory>
#include <string>
#include <vector>

#include "core/io/SeriesEntry.h"
#include "server/RenderWorker.h"

namespace lucent::remote {

class ClientConnection;

struct ServerOptions {
    QHostAddress address = QHostAddress::LocalHost;
    quint16 port = 0; // 0: any free port
    std::vector<std::string> tokens;
    Backend backend = Backend::Gl;
    int maxClients = 64;
};

// The tokens of a token file: one per line, blank lines and lines starting
// with '#' ignored. Throws std::runtime_error when it cannot be read or holds none.
std::vector<std::string> readTokenFile(const QString& path);

class RenderServer : public QObject {
    Q_OBJECT
public:
    // `series`: what clients may list and open (volumes only).
    RenderServer(ServerOptions options, std::vector<std::shared_ptr<const SeriesEntry>> series,
                 QObject* parent = nullptr);
    ~RenderServer() override;

    // Starts the render thread and listens. False with a message on failure.
    bool listen(QString* error);
    quint16 port() const;
    // What renders ("gl: llvmpipe ..." or "cpu ..."), once the render thread has started.
    const QString& backendDescription() const { return backendDescription_; }

    // For connections.
    bool acceptsToken(const std::string& token) const;
    const std::vector<std::shared_ptr<const SeriesEntry>>& series() const { return series_; }
    std::shared_ptr<const SeriesEntry> findSeries(const std::string& uid) const;
    void submit(const RenderJob& job);

private:
    void onNewConnection();
    void onFrameRendered(const RenderedFrame& frame);

    ServerOptions options_;
    std::vector<std::shared_ptr<const SeriesEntry>> series_;
    QWebSocketServer* socketServer_; // child
    QThread renderThread_;
    std::unique_ptr<RenderWorker> worker_; // lives on renderThread_; deleted after it ends
    QString backendDescription_;
    QHash<quint64, QPointer<ClientConnection>> clients_;
    quint64 nextClientId_ = 1;
};

} // namespace lucent::remote
