#include "server/RenderServer.h"

#include <QFile>
#include <QLoggingCategory>
#include <QMetaObject>

#include <algorithm>
#include <stdexcept>

#include <sys/stat.h>

#include "server/ClientConnection.h"
#include "server/ConstantTime.h"
#include "server/LocalFrameSource.h"
#include "server/TeachingSession.h"
#include "server/ViewMarks.h"
#include "server/ViewStream.h"

namespace lucent::remote {
namespace {

Q_LOGGING_CATEGORY(lcServer, "lucent.server")

// "0644" for a file's permission bits.
std::string octalMode(mode_t mode) {
    return QString::number(mode & 07777, 8).rightJustified(4, '0').toStdString();
}

// Throws unless only the file's owner may read or write it: tokens are
// passwords, and a token file that its group or others can read has leaked.
void checkOwnerOnly(const QFile& file) {
    struct stat info {};
    if (fstat(file.handle(), &info) != 0) {
        throw std::runtime_error("token file " + file.fileName().toStdString() +
                                 ": its mode cannot be read");
    }
    const mode_t shared = info.st_mode & (S_IRWXG | S_IRWXO);
    if (shared == 0) {
        return;
    }
    const std::string who = (shared & S_IRWXG) && (shared & S_IRWXO) ? "its group and others"
                            : (shared & S_IRWXG)                     ? "its group"
                                                                     : "others";
    const std::string path = file.fileName().toStdString();
    throw std::runtime_error("token file " + path + " has mode " + octalMode(info.st_mode) + ": " +
                             who + " may use it; only its owner may (chmod 600 " + path + ")");
}

} // namespace

std::vector<std::string> readTokenFile(const QString& path) {
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly | QIODevice::Text)) {
        throw std::runtime_error("token file " + path.toStdString() + " cannot be read");
    }
    checkOwnerOnly(file);
    std::vector<std::string> tokens;
    while (!file.atEnd()) {
        const QByteArray line = file.readLine().trimmed();
        if (!line.isEmpty() && !line.startsWith('#')) {
            tokens.emplace_back(line.constData(), std::size_t(line.size()));
        }
    }
    if (tokens.empty()) {
        throw std::runtime_error("token file " + path.toStdString() + " holds no token");
    }
    return tokens;
}

RenderServer::RenderServer(ServerOptions options, SeriesList storeSeries, SeriesList dataSeries,
                           QObject* parent)
    : QObject(parent), options_(std::move(options)), dataSeries_(std::move(dataSeries)),
      series_(mergeServedSeries(storeSeries, dataSeries_)),
      socketServer_(new QWebSocketServer("lucent-server", QWebSocketServer::NonSecureMode, this)),
      worker_(std::make_unique<RenderWorker>(
          options_.frameSource ? options_.frameSource()
                               : std::make_unique<LocalFrameSource>(options_.backend))) {
    qRegisterMetaType<lucent::remote::RenderedFrame>();
    qRegisterMetaType<lucent::remote::RenderedSlices>();
    scanPool_.setMaxThreadCount(1);
    worker_->moveToThread(&renderThread_);
    renderThread_.setObjectName("lucent-render");
    connect(worker_.get(), &RenderWorker::frameRendered, this, &RenderServer::onFrameRendered);
    qRegisterMetaType<lucent::remote::FoundAnchors>();
    connect(worker_.get(), &RenderWorker::anchorsFound, this, &RenderServer::onAnchorsFound);
    connect(worker_.get(), &RenderWorker::slicesRendered, this, &RenderServer::onSlicesRendered);
    connect(socketServer_, &QWebSocketServer::newConnection, this, &RenderServer::onNewConnection);
    // A client that offers a lucent.v<N> this server speaks gets it (its token may
    // ride in another subprotocol).
    QStringList versions;
    for (const std::string& name : supportedSubprotocols()) {
        versions << QString::fromStdString(name);
    }
    socketServer_->setSupportedSubprotocols(versions);
    removeStaleCopies();
}

RenderServer::~RenderServer() {
    scanPool_.waitForDone();
    copyPool_.waitForDone();
    socketServer_->close();
    for (const auto& client : std::as_const(clients_)) {
        if (client) {
            QObject::disconnect(client, nullptr, this, nullptr); // they go with this object
        }
    }
    // Sessions and clients unregister their views from this object's members:
    // they go first.
    for (const auto& session : std::as_const(sessions_)) {
        delete session.data();
    }
    for (const auto& client : std::as_const(clients_)) {
        delete client.data();
    }
    if (renderThread_.isRunning()) {
        QMetaObject::invokeMethod(
            worker_.get(), [worker = worker_.get()] { worker->stop(); },
            Qt::BlockingQueuedConnection);
        renderThread_.quit();
        renderThread_.wait();
    }
}

bool RenderServer::listen(QString* error) {
    renderThread_.start();
    QMetaObject::invokeMethod(
        worker_.get(), [this] { backendDescription_ = worker_->start(); },
        Qt::BlockingQueuedConnection);
    qCInfo(lcServer) << "rendering with" << backendDescription_;
    // One port for the browser client's files and the WebSocket upgrades.
    frontDoor_ = new HttpFrontDoor(*socketServer_, this);
    frontDoor_->setUploadRoute(
        {options_.uploadLimitBytes,
         [this](const QByteArray& token) { return acceptsToken(token.toStdString()); },
         QString::fromStdString((options_.storeDir / "tmp").string()),
         [this](QByteArray contentType, std::shared_ptr<const SpooledBody> body,
                std::function<void(int, QByteArray)> reply) {
             ingestUpload(std::move(contentType), std::move(body), std::move(reply));
         }});
    return frontDoor_->listen(options_.address, options_.port, options_.tls, error);
}

quint16 RenderServer::port() const {
    return frontDoor_ ? frontDoor_->port() : 0;
}

bool RenderServer::acceptsToken(const std::string& token) const {
    bool accepted = false;
    for (const std::string& known : options_.tokens) {
        accepted |= equalInConstantTime(token, known);
    }
    return accepted;
}

std::shared_ptr<const SeriesEntry> RenderServer::findSeries(const std::string& uid) const {
    for (const auto& s : series_) {
        if (s->id == uid) {
            return s;
        }
    }
    return nullptr;
}

void RenderServer::submit(const RenderJob& job) {
    if (!job.background) {
        dispatch(job);
        return;
    }
    RenderJob waiting = job;
    const bool busy = rendersOutstanding_ > 0 || !backgroundJobs_.empty();
    if (waiting.mayDegrade && busy) {
        // Cheaper while others wait: a still as the fixed interactive frame, a
        // drag's frame at most at half size and JPEG quality 60.
        if (waiting.quality == Quality::Still) {
            waiting.scale = kFixedInteractiveScale;
            waiting.jpegQuality = kFixedInteractiveJpegQuality;
        } else {
            waiting.scale = std::min(waiting.scale, kBusyInteractiveScale);
            waiting.jpegQuality = std::min(waiting.jpegQuality, kBusyInteractiveJpegQuality);
        }
        waiting.quality = Quality::Interactive;
        waiting.degraded = true;
    }
    backgroundJobs_.push_back(std::move(waiting));
    dispatchBackground();
}

void RenderServer::dispatch(const RenderJob& job) {
    ++rendersOutstanding_;
    QMetaObject::invokeMethod(
        worker_.get(), [worker = worker_.get(), job] { worker->render(job); },
        Qt::QueuedConnection);
}

void RenderServer::submitAnchors(const AnchorJob& job) {
    QMetaObject::invokeMethod(
        worker_.get(), [worker = worker_.get(), job] { worker->anchor(job); },
        Qt::QueuedConnection);
}

void RenderServer::dispatchBackground() {
    if (rendersOutstanding_ == 0 && !backgroundJobs_.empty()) {
        const RenderJob job = std::move(backgroundJobs_.front());
        backgroundJobs_.pop_front();
        dispatch(job);
    }
}

void RenderServer::submitSlices(const SliceJob& job) {
    QMetaObject::invokeMethod(
        worker_.get(), [worker = worker_.get(), job] { worker->renderSlices(job); },
        Qt::QueuedConnection);
}

void RenderServer::onNewConnection() {
    while (QWebSocket* socket = socketServer_->nextPendingConnection()) {
        const quint64 id = nextClientId_++;
        auto* client = new ClientConnection(id, socket, *this); // child of this server
        qCInfo(lcServer) << "client" << id << "connected from" << socket->peerAddress().toString();
        if (clients_.size() >= options_.maxClients) {
            client->sendError("busy", "the server has no room for another client", true);
        } else {
            client->start();
        }
        clients_.insert(id, client);
        connect(client, &ClientConnection::closed, this, [this](quint64 closedId) {
            if (const QPointer<ClientConnection> c = clients_.take(closedId)) {
                c->deleteLater();
            }
        });
    }
}

void RenderServer::onFrameRendered(const RenderedFrame& frame) {
    --rendersOutstanding_;
    if (const QPointer<ViewStream> view = views_.value(frame.view)) {
        view->deliver(frame); // its next job, if any, goes ahead of waiting free look
    }
    dispatchBackground();
}

void RenderServer::onAnchorsFound(const FoundAnchors& found) {
    if (const QPointer<ViewStream> view = views_.value(found.view)) {
        view->marks().anchored(found);
    }
}

void RenderServer::onSlicesRendered(const RenderedSlices& slices) {
    if (const QPointer<ViewStream> view = views_.value(slices.view)) {
        view->slices().deliver(slices);
    }
}

} // namespace lucent::remote
