#include "server/HttpFrontDoor.h"

#include <QEventLoop>
#include <QFile>
#include <QLoggingCategory>
#include <QRegularExpression>
#include <QSslCertificate>
#include <QSslKey>
#include <QSslServer>
#include <QSslSocket>
#include <QTcpServer>
#include <QTcpSocket>
#include <QTimer>
#include <QWebSocketServer>

#include <stdexcept>

namespace lucent::remote {
namespace {

Q_LOGGING_CATEGORY(lcHttp, "lucent.server.http")

// The embedded browser client (qt_add_resources in server/CMakeLists.txt).
constexpr char kClientRoot[] = ":/web/";
// Certificate and key files are read up to this size (a PEM chain is a few KiB).
constexpr qint64 kMaxPemBytes = 1 << 20;

std::runtime_error tlsError(const QString& message) {
    return std::runtime_error(message.toStdString());
}

QByteArray readWhole(const QString& path, const QString& what) {
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly)) {
        throw tlsError(what + " " + path + " cannot be read: " + file.errorString());
    }
    return file.read(kMaxPemBytes);
}

QSslKey parsePrivateKey(const QByteArray& pem) {
    for (const QSsl::KeyAlgorithm algorithm : {QSsl::Rsa, QSsl::Ec, QSsl::Dsa}) {
        QSslKey key(pem, algorithm, QSsl::Pem, QSsl::PrivateKey);
        if (!key.isNull()) {
            return key;
        }
    }
    return {};
}

// Serves one TLS handshake to itself over loopback: empty when the server side
// completes it, else why not (OpenSSL says when the key does not match).
QString selfHandshakeError(const QSslConfiguration& configuration) {
    QSslServer server;
    server.setSslConfiguration(configuration);
    if (!server.listen(QHostAddress::LocalHost, 0)) {
        return "no loopback port for the check: " + server.errorString();
    }
    QEventLoop loop;
    bool done = false;
    QString serverError;
    QObject::connect(&server, &QTcpServer::pendingConnectionAvailable, &loop, [&] {
        done = true;
        loop.quit();
    });
    QObject::connect(&server, &QSslServer::errorOccurred, &loop,
                     [&](QSslSocket* socket, QAbstractSocket::SocketError) {
                         serverError = socket->errorString();
                         loop.quit();
                     });
    QSslSocket client;
    client.setPeerVerifyMode(QSslSocket::VerifyNone);
    QTimer::singleShot(10000, &loop, &QEventLoop::quit);
    client.connectToHostEncrypted("127.0.0.1", server.serverPort());
    loop.exec();
    if (done) {
        return {};
    }
    return serverError.isEmpty() ? "no TLS handshake within 10 s" : serverError;
}

QByteArray reasonPhrase(int status) {
    switch (status) {
    case 200:
        return "OK";
    case 400:
        return "Bad Request";
    case 401:
        return "Unauthorized";
    case 411:
        return "Length Required";
    case 413:
        return "Content Too Large";
    case 415:
        return "Unsupported Media Type";
    case 500:
        return "Internal Server Error";
    case 404:
        return "Not Found";
    case 405:
        return "Method Not Allowed";
    case 408:
        return "Request Timeout";
    case 431:
        return "Request Header Fields Too Large";
    case 507:
        return "Insufficient Storage";
    default:
        return "Error";
    }
}

QByteArray contentTypeOf(const QString& name) {
    if (name.endsWith(".html")) {
        return "text/html; charset=utf-8";
    }
    if (name.endsWith(".js")) {
        return "text/javascript; charset=utf-8";
    }
    if (name.endsWith(".css")) {
        return "text/css; charset=utf-8";
    }
    if (name.endsWith(".svg")) {
        return "image/svg+xml";
    }
    if (name.endsWith(".png")) {
        return "image/png";
    }
    return "application/octet-stream";
}

// The embedded file a request path names, or empty. Only plain names of the
// client's folder: no sub-folders, no "..", no escapes.
QString clientFileFor(const QByteArray& target) {
    const qsizetype query = target.indexOf('?');
    const QByteArray path = query < 0 ? target : target.left(query);
    if (path == "/") {
        return QString(kClientRoot) + "index.html";
    }
    static const QRegularExpression plainName("^/[A-Za-z0-9][A-Za-z0-9_-]*(\\.[A-Za-z0-9]+)*$");
    const QString name = QString::fromLatin1(path);
    if (!plainName.match(name).hasMatch()) {
        return {};
    }
    const QString file = QString(kClientRoot) + name.mid(1);
    return QFile::exists(file) ? file : QString();
}

} // namespace

QSslConfiguration loadServerTls(const TlsFiles& files) {
    if (!QSslSocket::supportsSsl()) {
        throw tlsError("TLS is not available: Qt has no TLS backend (is OpenSSL installed?)");
    }
    const QList<QSslCertificate> chain =
        QSslCertificate::fromData(readWhole(files.certificate, "TLS certificate"), QSsl::Pem);
    if (chain.isEmpty() || chain.front().isNull()) {
        throw tlsError("TLS certificate " + files.certificate + " holds no PEM certificate");
    }
    const QSslKey key = parsePrivateKey(readWhole(files.key, "TLS key"));
    if (key.isNull()) {
        throw tlsError("TLS key " + files.key +
                       " holds no unencrypted PEM private key (RSA, EC or DSA)");
    }
    QSslConfiguration configuration = QSslConfiguration::defaultConfiguration();
    configuration.setLocalCertificateChain(chain);
    configuration.setPrivateKey(key);
    configuration.setPeerVerifyMode(
        QSslSocket::VerifyNone); // clients present tokens, not certificates
    if (const QString why = selfHandshakeError(configuration); !why.isEmpty()) {
        throw tlsError("TLS key " + files.key + " does not match certificate " + files.certificate +
                       " (a TLS handshake with them failed: " + why.trimmed() + ")");
    }
    return configuration;
}

HttpFrontDoor::HttpFrontDoor(QWebSocketServer& webSockets, QObject* parent)
    : QObject(parent), webSockets_(webSockets) {}

HttpFrontDoor::~HttpFrontDoor() = default;

bool HttpFrontDoor::listen(const QHostAddress& address, quint16 port,
                           const std::optional<TlsFiles>& tls, QString* error) {
    delete server_;
    secure_ = tls.has_value();
    if (tls) {
        auto* sslServer = new QSslServer(this);
        try {
            sslServer->setSslConfiguration(loadServerTls(*tls));
        } catch (const std::exception& e) {
            delete sslServer;
            server_ = nullptr;
            *error = QString::fromStdString(e.what());
            return false;
        }
        connect(sslServer, &QSslServer::errorOccurred, this,
                [](QSslSocket*, QAbstractSocket::SocketError code) {
                    qCInfo(lcHttp) << "TLS connection refused:" << code;
                });
        server_ = sslServer;
    } else {
        server_ = new QTcpServer(this);
    }
    // QSslServer offers a connection once its handshake is done.
    connect(server_, &QTcpServer::pendingConnectionAvailable, this,
            &HttpFrontDoor::onPendingConnection);
    if (!server_->listen(address, port)) {
        *error = "cannot listen on " + address.toString() + ":" + QString::number(port) + ": " +
                 server_->errorString();
        return false;
    }
    return true;
}

void HttpFrontDoor::close() {
    if (server_) {
        server_->close();
    }
}

quint16 HttpFrontDoor::port() const {
    return server_ ? server_->serverPort() : 0;
}

void HttpFrontDoor::onPendingConnection() {
    while (QTcpSocket* socket = server_->nextPendingConnection()) {
        if (waitingForHead_.size() >= kMaxConnectionsWaitingForHead) {
            qCInfo(lcHttp) << "too many connections without a request head; one closed";
            socket->abort();
            socket->deleteLater();
            continue;
        }
        waitingForHead_.insert(socket);
        connect(socket, &QObject::destroyed, this,
                [this, socket] { waitingForHead_.remove(socket); });
        auto* deadline = new QTimer(socket);
        deadline->setObjectName(kHeadTimerName);
        deadline->setSingleShot(true);
        connect(deadline, &QTimer::timeout, socket,
                [this, socket, deadline] { onDeadline(socket, *deadline); });
        deadline->start(kRequestHeadTimeoutMs);
        connect(socket, &QTcpSocket::readyRead, this, [this, socket] { onReadable(socket); });
        connect(socket, &QTcpSocket::disconnected, this, [socket] { socket->deleteLater(); });
        if (socket->bytesAvailable() > 0) {
            onReadable(socket);
        }
    }
}

void HttpFrontDoor::onDeadline(QTcpSocket* socket, QTimer& deadline) {
    if (!waitingForHead_.contains(socket)) {
        socket->abort(); // no answer, no body, or a 408 not taken: dropped
        return;
    }
    // A slow (or stalled) client: told why, then dropped if it does not go.
    waitingForHead_.remove(socket);
    disconnect(socket, &QTcpSocket::readyRead, this, nullptr);
    deadline.start(kClosingGraceMs);
    respond(socket, 408, "text/plain; charset=utf-8",
            "the request head did not arrive within " +
                QByteArray::number(kRequestHeadTimeoutMs / 1000) + " s\n",
            true);
}

void HttpFrontDoor::onReadable(QTcpSocket* socket) {
    // Peek, not read: an upgrade goes to QWebSocketServer with its head unread.
    const QByteArray peeked = socket->peek(kMaxRequestHeadBytes + 1);
    const qsizetype end = peeked.indexOf("\r\n\r\n");
    if (end < 0) {
        if (peeked.size() > kMaxRequestHeadBytes) {
            waitingForHead_.remove(socket);
            disconnect(socket, &QTcpSocket::readyRead, this, nullptr);
            respond(socket, 431, "text/plain; charset=utf-8",
                    "the request head is larger than " + QByteArray::number(kMaxRequestHeadBytes) +
                        " bytes\n",
                    true);
        }
        return;
    }
    waitingForHead_.remove(socket);
    disconnect(socket, &QTcpSocket::readyRead, this, nullptr);
    const std::optional<HttpRequestHead> request = parseHttpRequestHead(peeked.left(end + 4));
    if (request && request->isWebSocketUpgrade()) {
        delete socket->findChild<QTimer*>(kHeadTimerName); // QWebSocketServer takes over
        disconnect(socket, nullptr, this, nullptr);
        webSockets_.handleConnection(socket);
        return;
    }
    (void)socket->read(end + 4);
    if (auto* deadline = socket->findChild<QTimer*>(kHeadTimerName)) {
        deadline->start(kAnswerTimeoutMs);
    }
    if (!request) {
        respond(socket, 400, "text/plain; charset=utf-8", "not an HTTP/1.1 request\n", true);
        return;
    }
    answer(socket, *request);
}

void HttpFrontDoor::answer(QTcpSocket* socket, const HttpRequestHead& request) {
    const bool head = request.method == "HEAD";
    if (request.method == "POST" && upload_.store && isUploadTarget(request.target)) {
        receiveUpload(socket, request);
        return;
    }
    if (request.method != "GET" && !head) {
        respond(socket, 405, "text/plain; charset=utf-8",
                upload_.store ? "only GET and HEAD are served here (uploads: POST /studies)\n"
                              : "only GET and HEAD are served here\n",
                true, "Allow: GET, HEAD\r\n");
        return;
    }
    const QString name = clientFileFor(request.target);
    QFile file(name);
    if (name.isEmpty() || !file.open(QIODevice::ReadOnly)) {
        respond(socket, 404, "text/plain; charset=utf-8", "not found\n", !head);
        return;
    }
    QByteArray extra;
    if (name.endsWith(".html")) {
        // The page may talk only to this server (WebSocket included) and run only its own script.
        extra = "Content-Security-Policy: default-src 'self'; connect-src 'self' ws: wss:; "
                "img-src 'self' blob: data:; frame-ancestors 'none'\r\n";
    }
    respond(socket, 200, contentTypeOf(name), file.readAll(), !head, extra);
}

void HttpFrontDoor::respond(QTcpSocket* socket, int status, const QByteArray& contentType,
                            const QByteArray& body, bool withBody, const QByteArray& extraFields) {
    qCDebug(lcHttp) << "HTTP" << status;
    QByteArray response =
        "HTTP/1.1 " + QByteArray::number(status) + " " + reasonPhrase(status) +
        "\r\nContent-Type: " + contentType +
        "\r\nContent-Length: " + QByteArray::number(body.size()) +
        "\r\nConnection: close\r\nCache-Control: no-cache"
        "\r\nX-Content-Type-Options: nosniff\r\nReferrer-Policy: no-referrer\r\n" +
        extraFields + "\r\n";
    if (withBody) {
        response += body;
    }
    socket->write(response);
    socket->disconnectFromHost();
}

} // namespace lucent::remote
