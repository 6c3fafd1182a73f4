// HttpFrontDoor: POST /studies, instances uploaded into the server's store,
// authorized by "Authorization: Bearer <token>", at most UploadRoute::limitBytes,
// spooled to a file as they arrive.
#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <QLoggingCategory>
#include <QPointer>
#include <QTcpSocket>
#include <QTemporaryFile>
#include <QTimer>

#include <algorithm>
#include <memory>

#include "server/HttpFrontDoor.h"

namespace lucent::remote {
namespace {

Q_LOGGING_CATEGORY(lcUpload, "lucent.server.upload")

constexpr char kText[] = "text/plain; charset=utf-8";
// The folder and the system's reason go to the log, not to the client.
constexpr char kCannotSpool[] = "the server cannot write the upload to its store's disk (full or "
                                "not writable); its log says more\n";
// Read and written at most this much at a time.
constexpr qint64 kChunk = qint64(1) << 20;
// An upload whose body is in is answered within this time, or its connection closed.
constexpr int kStoreTimeoutMs = 10 * 60 * 1000;

} // namespace

SpooledBody::~SpooledBody() {
    QFile::remove(path_);
}

bool isUploadTarget(const QByteArray& target) {
    const qsizetype query = target.indexOf('?');
    const QByteArray path = query < 0 ? target : target.left(query);
    return path == "/studies" || path == "/studies/";
}

void HttpFrontDoor::receiveUpload(QTcpSocket* socket, const HttpRequestHead& request) {
    if (!request.field("transfer-encoding").isEmpty()) {
        respond(socket, 411, kText,
                "send the upload with a Content-Length (chunked bodies are not accepted)\n", true);
        return;
    }
    bool isNumber = false;
    const qint64 length = request.field("content-length").toLongLong(&isNumber);
    if (!isNumber || length < 0) {
        respond(socket, 411, kText, "the upload has no Content-Length (or not a number)\n", true);
        return;
    }
    int refusal = 0;
    QByteArray message;
    QByteArray extra;
    const QByteArray authorization = request.field("authorization");
    if (authorization.isEmpty()) {
        refusal = 401;
        message = "an upload needs a token: 'Authorization: Bearer <token>'\n";
    } else if (!authorization.toLower().startsWith("bearer ") ||
               !upload_.acceptsToken(authorization.mid(7).trimmed())) {
        refusal = 401;
        message = "the token in 'Authorization: Bearer' is not accepted\n";
    } else if (length > upload_.limitBytes) {
        refusal = 413;
        message = "the upload is " + QByteArray::number(length) +
                  " bytes; this server accepts at most " + QByteArray::number(upload_.limitBytes) +
                  "\n";
    }
    if (refusal == 401) {
        extra = "WWW-Authenticate: Bearer\r\n";
    }
    const bool expectsContinue = request.field("expect").toLower() == "100-continue";
    if (refusal != 0) {
        if (expectsContinue || length > kMaxDrainedUploadBytes) {
            respond(socket, refusal, kText, message, true, extra); // the body is not read
        } else {
            readBody(
                socket, length, [](const QByteArray&) { return true; },
                [this, socket, refusal, message, extra] {
                    respond(socket, refusal, kText, message, true, extra);
                });
        }
        return;
    }
    // The body goes to a file as it arrives: an upload of the full limit costs
    // that much disk for a moment, never that much memory.
    QDir().mkpath(upload_.spoolDir);
    QTemporaryFile created(
        QDir(upload_.spoolDir)
            .filePath(
                QString("incoming-%1-upload-XXXXXX.part").arg(QCoreApplication::applicationPid())));
    created.setAutoRemove(false);
    if (!created.open()) {
        qCWarning(lcUpload) << "cannot spool an upload in" << upload_.spoolDir << ":"
                            << created.errorString();
        respond(socket, 507, kText, kCannotSpool, true);
        return;
    }
    auto body = std::make_shared<SpooledBody>(created.fileName());
    auto file = std::make_shared<QFile>(created.fileName());
    created.close();
    if (!file->open(QIODevice::WriteOnly)) {
        qCWarning(lcUpload) << "cannot write" << body->path() << ":" << file->errorString();
        respond(socket, 507, kText, kCannotSpool, true);
        return;
    }
    if (expectsContinue) {
        socket->write("HTTP/1.1 100 Continue\r\n\r\n");
    }
    readBody(
        socket, length,
        [this, socket, file](const QByteArray& chunk) {
            // Flushed per chunk: what has arrived is on disk, not in a buffer.
            if (file->write(chunk) == chunk.size() && file->flush()) {
                return true;
            }
            qCWarning(lcUpload) << "cannot write" << file->fileName() << ":" << file->errorString();
            respond(socket, 507, kText, kCannotSpool, true);
            return false;
        },
        [this, socket, file, body, contentType = request.field("content-type")] {
            file->close();
            // The client has sent all: checking and storing a large upload may
            // take longer than it is given to send, though not for ever, and
            // what it sends meanwhile is not taken in.
            socket->setReadBufferSize(kChunk);
            if (auto* deadline = socket->findChild<QTimer*>(kHeadTimerName)) {
                deadline->start(kStoreTimeoutMs);
            }
            upload_.store(
                contentType, body,
                [this, guarded = QPointer<QTcpSocket>(socket)](int status, QByteArray answer) {
                    if (guarded) {
                        respond(guarded, status, status == 200 ? "application/json" : kText, answer,
                                true);
                    }
                });
        });
}

void HttpFrontDoor::readBody(QTcpSocket* socket, qint64 length,
                             std::function<bool(const QByteArray&)> consume,
                             std::function<void()> done) {
    struct Progress {
        qint64 read = 0;
        bool finished = false;
        std::function<bool(const QByteArray&)> consume;
        std::function<void()> done;
    };
    auto progress = std::make_shared<Progress>();
    progress->consume = std::move(consume);
    progress->done = std::move(done);
    const auto onData = [socket, length, progress] {
        bool moved = false;
        while (!progress->finished && progress->read < length && socket->bytesAvailable() > 0) {
            const QByteArray chunk =
                socket->read(std::min<qint64>(length - progress->read, kChunk));
            progress->read += chunk.size();
            moved = moved || !chunk.isEmpty();
            if (!chunk.isEmpty() && !progress->consume(chunk)) {
                progress->finished = true;
                QObject::disconnect(socket, &QTcpSocket::readyRead, nullptr, nullptr);
                return;
            }
        }
        if (progress->finished) {
            return;
        }
        if (auto* deadline = socket->findChild<QTimer*>(kHeadTimerName); deadline && moved) {
            deadline->start(kAnswerTimeoutMs); // a slow upload may go on while it moves
        }
        if (progress->read == length) {
            progress->finished = true;
            const auto finish = std::move(progress->done);
            QObject::disconnect(socket, &QTcpSocket::readyRead, nullptr, nullptr);
            finish();
        }
    };
    connect(socket, &QTcpSocket::readyRead, this, onData);
    onData();
}

} // namespace lucent::remote
