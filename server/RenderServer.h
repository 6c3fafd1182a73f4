#pragma once
// lucent-server's core: a WebSocket server (protocol v1, docs/protocol.md)
// that authenticates clients with tokens, lists the series it holds, and
// renders each client's view on one render thread.

#include <QHash>
#include <QHostAddress>
#include <QObject>
#include <QPointer>
#include <QString>
#include <QThread>
#include <QThreadPool>
#include <QWebSocketServer>

#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/io/SeriesEntry.h"
#include "render/RenderDevice.h"
#include "server/HttpFrontDoor.h"
#include "server/InviteBook.h"
#include "server/RenderWorker.h"
#include "server/ServedSeries.h"

namespace lucent::remote {

class ClientConnection;
class TeachingSession;
class ViewStream;

struct ServerOptions {
    QHostAddress address = QHostAddress::LocalHost;
    quint16 port = 0; // 0: any free port
    std::vector<std::string> tokens;
    RendererKind backend = RendererKind::Gl;
    // Where frames are drawn; empty: in this process, with `backend`
    // (LocalFrameSource). Called once, on the thread that makes the server.
    std::function<std::unique_ptr<FrameSource>()> frameSource;
    int maxClients = 64;
    int maxSessions = 16;
    int maxSessionMembers = 64; // the presenter included
    int maxFreeLook = 16;       // followers of one session in free look at once
    // Each client is pinged this often; one silent for three intervals (no
    // pong, no message) is dropped, which frees its place in a session.
    int keepaliveSeconds = 20;
    // The store: de-identified copies for teaching sessions go under it.
    std::filesystem::path storeDir;
    std::optional<TlsFiles> tls; // https:// and wss:// on the same port when set
    // Uploads (POST /studies) larger than this are refused with 413.
    qint64 uploadLimitBytes = qint64(512) << 20;
};

// The tokens of a token file: one per line, blank lines and lines starting
// with '#' ignored. Throws std::runtime_error when it cannot be read, when its
// group or others may read, write or run it (mode 0600 or stricter is needed),
// or when it holds no token.
std::vector<std::string> readTokenFile(const QString& path);

class RenderServer : public QObject {
    Q_OBJECT
public:
    // What clients may list and open (volumes only): the store's series, which
    // rescanStore() refreshes, and those of the data path, fixed.
    RenderServer(ServerOptions options, SeriesList storeSeries, SeriesList dataSeries,
                 QObject* parent = nullptr);
    ~RenderServer() override;

    // Starts the render thread and listens. False with a message on failure.
    bool listen(QString* error);
    quint16 port() const;
    // What renders ("gl: llvmpipe ..." or "cpu ..."), once the render thread has started.
    const QString& backendDescription() const { return backendDescription_; }

    // For connections.
    bool acceptsToken(const std::string& token) const;
    InviteBook& invites() { return invites_; }
    bool servesTls() const { return options_.tls.has_value(); }
    int keepaliveSeconds() const { return options_.keepaliveSeconds; }
    // The store (recordings, de-identified copies); empty when the server has none.
    const std::filesystem::path& storeDir() const { return options_.storeDir; }
    const SeriesList& series() const { return series_; }
    std::shared_ptr<const SeriesEntry> findSeries(const std::string& uid) const;
    int maxFreeLook() const { return options_.maxFreeLook; }
    // Hands a job to the render thread. A background job (free look) waits
    // until no other job is outstanding there, so sessions and clients' own
    // views go first; one asked for while the render thread is busy (a job is
    // outstanding or another background job waits) is, when mayDegrade, made
    // cheaper (RenderedFrame::degraded): a still an interactive frame, an
    // interactive one at most kBusyInteractiveScale and kBusyInteractiveJpegQuality.
    void submit(const RenderJob& job);
    // Anchors a mark on the render thread; the view's marks get the points (ViewMarks).
    void submitAnchors(const AnchorJob& job);
    void submitSlices(const SliceJob& job);

    // Scans the store's files again (on a worker thread) and serves what it
    // holds from then on; `done` runs on this thread when the new list is in
    // place. Scans asked for while one runs are done once, after it.
    void rescanStore(std::function<void()> done = {});
    // Stores the instances of an upload (POST /studies; see UploadIngest.h),
    // then rescans; `reply` gets the HTTP status and body on this thread.
    void ingestUpload(QByteArray contentType, std::shared_ptr<const SpooledBody> body,
                      std::function<void(int, QByteArray)> reply);

    // Views and the frames rendered for them.
    quint64 newViewId() { return nextViewId_++; }
    void registerView(ViewStream* view);
    void unregisterView(quint64 id);

    // Teaching sessions. createSession() gives null at the limit.
    TeachingSession* createSession(ClientConnection& presenter);
    TeachingSession* findSession(const QString& id) const;
    void endSession(const QString& id);
    int sessionCount() const { return int(sessions_.size()); }
    // The de-identified copy of a series (made once, under the store, on a
    // worker thread); `done` runs on this thread unless `context` is gone,
    // with null and the reason when it failed.
    using CopyDone = std::function<void(std::shared_ptr<const SeriesEntry>, QString)>;
    void deidentifiedCopy(const std::shared_ptr<const SeriesEntry>& original, QObject* context,
                          CopyDone done);

private:
    void onNewConnection();
    void onFrameRendered(const RenderedFrame& frame);
    void onAnchorsFound(const FoundAnchors& found);
    void dispatch(const RenderJob& job);
    void dispatchBackground();
    void onSlicesRendered(const RenderedSlices& slices);
    void copyFinished(const std::string& originalId, std::shared_ptr<const SeriesEntry> copy,
                      const QString& error);
    // Copies of an earlier run are stale (their sessions are gone): removed at start.
    void removeStaleCopies();

    void setStoreSeries(const SeriesList& storeSeries);

    ServerOptions options_;
    SeriesList dataSeries_;
    SeriesList series_;    // the store's, then the data path's
    QThreadPool scanPool_; // one thread: store scans and uploads, in order
    bool scanRunning_ = false;
    std::vector<std::function<void()>> scanWaiters_; // of the running scan
    std::vector<std::function<void()>> scanQueued_;  // of the next one
    bool scanAgain_ = false;
    QWebSocketServer* socketServer_;     // child
    HttpFrontDoor* frontDoor_ = nullptr; // child, made by listen(): the port, HTTP and TLS
    QThread renderThread_;
    std::unique_ptr<RenderWorker> worker_; // lives on renderThread_; deleted after it ends
    QString backendDescription_;
    QHash<quint64, QPointer<ClientConnection>> clients_;
    quint64 nextClientId_ = 1;
    QHash<quint64, QPointer<ViewStream>> views_;
    quint64 nextViewId_ = 1;
    int rendersOutstanding_ = 0;           // handed to the render thread, not yet back
    std::deque<RenderJob> backgroundJobs_; // free look, waiting for an idle render thread
    QHash<QString, QPointer<TeachingSession>> sessions_;
    InviteBook invites_;
    // De-identified copies by original series id, and who waits for one.
    std::map<std::string, std::shared_ptr<const SeriesEntry>> copies_;
    std::map<std::string, std::vector<std::pair<QPointer<QObject>, CopyDone>>> copyWaiters_;
    QThreadPool copyPool_; // makes the copies; waited for before the rest goes
};

} // namespace lucent::remote
