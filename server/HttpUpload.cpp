// HttpFrontDoor: POST /studies, instances uploaded into the server's store,
// authorized by "Authorization: Bearer <token>", at most UploadRoute::limitBytes.
#include <QPointer>
#include <QTcpSocket>
#include <QTimer>

#include <memory>

#include "server/HttpFrontDoor.h"

namespace lucent::remote {
namespace {

constexpr char kText[] = "text/plain; charset=utf-8";

} // namespace

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
            readBody(socket, length, false, [this, socket, refusal, message, extra](QByteArray) {
                respond(socket, refusal, kText, message, true, extra);
            });
        }
        return;
    }
    if (expectsContinue) {
        socket->write("HTTP/1.1 100 Continue\r\n\r\n");
    }
    readBody(socket, length, true,
             [this, socket, contentType = request.field("content-type")](QByteArray body) {
                 upload_.store(
                     contentType, std::move(body),
                     [this, guarded = QPointer<QTcpSocket>(socket)](int status, QByteArray answer) {
                         if (guarded) {
                             respond(guarded, status, status == 200 ? "application/json" : kText,
                                     answer, true);
                         }
                     });
             });
}

void HttpFrontDoor::readBody(QTcpSocket* socket, qint64 length, bool keep,
                             std::function<void(QByteArray)> done) {
    struct Progress {
        QByteArray body;
        qint64 read = 0;
        bool finished = false;
        std::function<void(QByteArray)> done;
    };
    auto progress = std::make_shared<Progress>();
    progress->done = std::move(done);
    if (keep) {
        progress->body.reserve(length);
    }
    const auto onData = [socket, length, keep, progress] {
        if (progress->finished) {
            return;
        }
        const QByteArray chunk = socket->read(length - progress->read);
        progress->read += chunk.size();
        if (keep) {
            progress->body.append(chunk);
        }
        if (auto* deadline = socket->findChild<QTimer*>(kHeadTimerName);
            deadline && !chunk.isEmpty()) {
            deadline->start(kAnswerTimeoutMs); // a slow upload may go on while it moves
        }
        if (progress->read == length) {
            progress->finished = true;
            const auto finish = std::move(progress->done);
            QObject::disconnect(socket, &QTcpSocket::readyRead, nullptr, nullptr);
            finish(std::move(progress->body));
        }
    };
    connect(socket, &QTcpSocket::readyRead, this, onData);
    onData();
}

} // namespace lucent::remote
