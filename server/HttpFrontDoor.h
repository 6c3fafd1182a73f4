#pragma once
// The render server's one port. Reads the head of each incoming HTTP request:
// a WebSocket upgrade goes to the QWebSocketServer, a GET of / or of a file of
// the browser client is answered from the files embedded from resources/web/,
// anything else is refused (404, 405, 400; 431 for an oversized head, 408 for
// one that does not arrive in time). With a TLS certificate the same port
// speaks https:// and wss:// (QSslServer).

#include <QByteArray>
#include <QHostAddress>
#include <QObject>
#include <QSet>
#include <QSslConfiguration>
#include <QString>

#include "server/HttpRequestHead.h"

#include <functional>
#include <memory>
#include <optional>

class QTcpServer;
class QTcpSocket;
class QTimer;
class QWebSocketServer;

namespace lucent::remote {

// A PEM certificate (chain, leaf first) and its PEM private key.
struct TlsFiles {
    QString certificate;
    QString key;
};

// The server side of TLS from these files. Throws std::runtime_error naming the
// file when one cannot be read or parsed, or when the key does not belong to the
// certificate (checked with a TLS handshake over loopback).
QSslConfiguration loadServerTls(const TlsFiles& files);

// Request heads larger than this are refused with 431.
inline constexpr qsizetype kMaxRequestHeadBytes = 16 * 1024;
// A connection that has not sent a whole request head by then (counted from
// its start, however slowly its bytes trickle in) is answered 408 and closed.
inline constexpr int kRequestHeadTimeoutMs = 10000;
// A connection told 408 that does not close is dropped this much later.
inline constexpr int kClosingGraceMs = 2000;
// Once its head is read, a request's connection is closed after this long
// without an answer or (uploads) without a byte of body.
inline constexpr int kAnswerTimeoutMs = 60000;
// The object name of the timer (a child of the socket) that enforces both timeouts.
inline constexpr char kHeadTimerName[] = "lucent-request-head-timer";
// At most this many connections may wait for their request head; more are closed at once.
inline constexpr int kMaxConnectionsWaitingForHead = 128;

// An upload's body, written to a file as it arrives so that an upload costs
// disk, not memory; the file is removed with its last owner.
class SpooledBody {
public:
    explicit SpooledBody(QString path) : path_(std::move(path)) {}
    ~SpooledBody();
    SpooledBody(const SpooledBody&) = delete;
    SpooledBody& operator=(const SpooledBody&) = delete;
    const QString& path() const { return path_; }

private:
    QString path_;
};

// POST /studies: instances uploaded into the server's store (server/HttpUpload.cpp).
struct UploadRoute {
    qint64 limitBytes = 0;                                     // larger bodies: 413
    std::function<bool(const QByteArray& token)> acceptsToken; // of "Authorization: Bearer"
    // Where bodies are spooled (the store's tmp/: a name with this process's
    // id there survives the store's clean-up while the process runs).
    QString spoolDir;
    // Gets the Content-Type and the whole body, spooled; answers through
    // `reply` (200 with JSON, else a status and a line of text) on the front
    // door's thread.
    std::function<void(QByteArray contentType, std::shared_ptr<const SpooledBody> body,
                       std::function<void(int status, QByteArray body)> reply)>
        store;
};
// True for /studies (the upload route's path), with or without a query.
bool isUploadTarget(const QByteArray& target);
// A refused upload's body is read and dropped up to this size before the
// answer (so that the client sees the answer, not a reset); larger ones are
// answered at once and the connection closed.
inline constexpr qint64 kMaxDrainedUploadBytes = qint64(64) << 20;

class HttpFrontDoor : public QObject {
    Q_OBJECT
public:
    // `webSockets` gets the upgraded connections; it need not listen itself.
    explicit HttpFrontDoor(QWebSocketServer& webSockets, QObject* parent = nullptr);
    ~HttpFrontDoor() override;

    // Listens with TLS when `tls` is given. False with a message (naming the
    // file for TLS problems) on failure.
    bool listen(const QHostAddress& address, quint16 port, const std::optional<TlsFiles>& tls,
                QString* error);
    void close();
    quint16 port() const;
    bool isSecure() const { return secure_; }
    // Accepts uploads at POST /studies (none without a route).
    void setUploadRoute(UploadRoute route) { upload_ = std::move(route); }

private:
    void onPendingConnection();
    void onReadable(QTcpSocket* socket);
    // The timer of kHeadTimerName went off: 408 while waiting for the head, else abort.
    void onDeadline(QTcpSocket* socket, QTimer& deadline);
    void answer(QTcpSocket* socket, const HttpRequestHead& request);
    void receiveUpload(QTcpSocket* socket, const HttpRequestHead& request);
    // Reads `length` bytes of body, each chunk to `consume` (which answers and
    // returns false to stop reading), then calls `done`.
    void readBody(QTcpSocket* socket, qint64 length,
                  std::function<bool(const QByteArray& chunk)> consume, std::function<void()> done);
    void respond(QTcpSocket* socket, int status, const QByteArray& contentType,
                 const QByteArray& body, bool withBody,
                 const QByteArray& extraFields = QByteArray());

    QWebSocketServer& webSockets_;
    QTcpServer* server_ = nullptr; // child; a QSslServer when secure
    QSet<const QTcpSocket*> waitingForHead_;
    bool secure_ = false;
    UploadRoute upload_;
};

} // namespace lucent::remote
