#pragma once
// For test_remote_abuse: the clients that misbehave towards lucent-server
// (raw TCP for what a well-behaved library would not send) and a reading of
// the server process's memory.

#include <QElapsedTimer>
#include <QFile>
#include <QTcpSocket>
#include <QWebSocket>

#include <memory>

namespace lucent::test {

// VmRSS and VmHWM of a process, in KiB (0 when unreadable).
struct ProcessMemory {
    qint64 rssKiB = 0;
    qint64 peakKiB = 0;
};

inline ProcessMemory readProcessMemory(qint64 pid) {
    QFile status(QString("/proc/%1/status").arg(pid));
    ProcessMemory m;
    if (!status.open(QIODevice::ReadOnly)) {
        return m;
    }
    for (const QByteArray& line : status.readAll().split('\n')) {
        const QList<QByteArray> parts = line.simplified().split(' ');
        if (parts.size() >= 2 && parts[0] == "VmRSS:") {
            m.rssKiB = parts[1].toLongLong();
        } else if (parts.size() >= 2 && parts[0] == "VmHWM:") {
            m.peakKiB = parts[1].toLongLong();
        }
    }
    return m;
}

// A WebSocket client that sends what it is given and records the server's
// error replies and how the server closed the connection.
class JunkClient {
public:
    explicit JunkClient(quint16 port) {
        QObject::connect(&socket, &QWebSocket::textMessageReceived, [this](const QString& text) {
            if (text.contains("\"type\":\"error\"")) {
                ++errors;
            }
        });
        QObject::connect(&socket, &QWebSocket::disconnected, [this] { closed = true; });
        QObject::connect(&socket, qOverload<QAbstractSocket::SocketError>(&QWebSocket::error),
                         [this](QAbstractSocket::SocketError error) {
                             reset = reset || error == QAbstractSocket::RemoteHostClosedError;
                         });
        socket.open(QUrl(QString("ws://127.0.0.1:%1/").arg(port)));
    }
    QWebSocket socket;
    int errors = 0;
    bool closed = false;
    // The connection ended without a close handshake (a reset).
    bool reset = false;
};

// A raw TCP connection to the server's port: what it received, and whether
// (and how long after it connected) the server closed it.
class RawClient {
public:
    explicit RawClient(quint16 port) {
        QObject::connect(&socket, &QTcpSocket::readyRead, [this] { received += socket.readAll(); });
        QObject::connect(&socket, &QTcpSocket::disconnected, [this] {
            closed = true;
            closedAfterMs = clock.elapsed();
        });
        clock.start();
        socket.connectToHost(QHostAddress::LocalHost, port);
    }
    QTcpSocket socket;
    QByteArray received;
    bool closed = false;
    qint64 closedAfterMs = -1;
    QElapsedTimer clock;
};

// The head of a WebSocket upgrade request (RFC 6455's sample key).
inline QByteArray upgradeHead(quint16 port, const QByteArray& extraFields = {}) {
    return "GET / HTTP/1.1\r\nHost: 127.0.0.1:" + QByteArray::number(port) +
           "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
           "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n" +
           extraFields + "\r\n";
}

// The first `sent` bytes of a masked client text frame that announces `length`
// bytes of payload (16-bit length form).
inline QByteArray partialTextFrame(quint16 length, int sent) {
    QByteArray frame;
    frame.append(char(0x81));        // FIN, text
    frame.append(char(0x80 | 126));  // masked, 16-bit length follows
    frame.append(char(length >> 8)); // network order
    frame.append(char(length & 0xff));
    frame.append("\x12\x34\x56\x78", 4); // mask
    frame.append(QByteArray(sent, 'j'));
    return frame;
}

} // namespace lucent::test
