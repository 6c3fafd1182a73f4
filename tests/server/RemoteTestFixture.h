#pragma once
// For the remote tests: a real lucent-server process (tests/support/ServerProcess.h)
// and a WebSocket client that records every message it receives.

#include <QElapsedTimer>
#include <QImage>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTest>
#include <QWebSocket>
#include <QWebSocketHandshakeOptions>

#include <cmath>
#include <functional>
#include <memory>

#include "core/image/Image.h"
#include "core/scene/RenderDescription.h"
#include "protocol/ProtocolMessages.h"
#include "tests/support/ServerProcess.h"

namespace lucent::test {

struct ReceivedFrame {
    remote::FrameHeader header;
    QByteArray image;

    ImageRGBA8 decoded() const {
        const QImage q = QImage::fromData(image).convertToFormat(QImage::Format_RGBA8888);
        ImageRGBA8 out = ImageRGBA8::filled(q.width(), q.height());
        for (int y = 0; y < q.height(); ++y) {
            std::copy_n(q.constScanLine(y), 4 * q.width(), out.at(0, y));
        }
        return out;
    }
};

// What a server renders for a view opened at side x side with ct-bone and
// given `camera`: the local reference of the remote tests.
inline RenderDescription referenceDescription(const Volume& volume, const Camera& camera,
                                              int side) {
    RenderDescription d;
    d.volume = &volume;
    d.width = side;
    d.height = side;
    d.transferFunction = loadPreset("ct-bone");
    d.camera = camera;
    return d;
}

class RemoteTestClient {
public:
    // `subprotocols`: offered in the handshake (a token may ride in one).
    explicit RemoteTestClient(quint16 port, const QStringList& subprotocols = {}) {
        QObject::connect(&socket_, &QWebSocket::textMessageReceived, [this](const QString& t) {
            texts.append(QJsonDocument::fromJson(t.toUtf8()).object());
        });
        QObject::connect(&socket_, &QWebSocket::binaryMessageReceived, [this](const QByteArray& b) {
            const auto parsed =
                remote::parseFrameMessage(std::string_view(b.constData(), std::size_t(b.size())));
            // MPR slices (version 4) apart from the 3D view's frames.
            (parsed.header.slice ? sliceFrames : frames)
                .append({parsed.header,
                         QByteArray(parsed.image.data(), qsizetype(parsed.image.size()))});
        });
        QObject::connect(&socket_, &QWebSocket::disconnected, [this] { disconnected = true; });
        const QUrl url(QString("ws://127.0.0.1:%1/").arg(port));
        if (subprotocols.isEmpty()) {
            socket_.open(url);
        } else {
            QWebSocketHandshakeOptions options;
            options.setSubprotocols(subprotocols);
            socket_.open(QNetworkRequest(url), options);
        }
    }

    bool waitConnected() {
        return QTest::qWaitFor(
            [this] { return socket_.state() == QAbstractSocket::ConnectedState; }, 10000);
    }
    void send(const QJsonObject& message) {
        socket_.sendTextMessage(
            QString::fromUtf8(QJsonDocument(message).toJson(QJsonDocument::Compact)));
    }
    void sendRaw(const QString& text) { socket_.sendTextMessage(text); }
    // Sends a view message and counts it (the server numbers accepted changes).
    void change(const QJsonObject& message) {
        send(message);
        ++seq;
    }

    // The first received text message (from index `from`) of this type; empty after timeout.
    QJsonObject waitForText(const QString& type, int timeoutMs = 20000, qsizetype from = 0) {
        QJsonObject found;
        (void)QTest::qWaitFor(
            [&] {
                for (qsizetype n = from; n < texts.size(); ++n) {
                    if (texts[n]["type"].toString() == type) {
                        found = texts[n];
                        return true;
                    }
                }
                return false;
            },
            timeoutMs);
        return found;
    }
    // Waits for the frame of the latest change; null when none came.
    const ReceivedFrame* waitForCurrentFrame(int timeoutMs = 60000) {
        (void)QTest::qWaitFor([&] { return !frames.isEmpty() && frames.back().header.seq >= seq; },
                              timeoutMs);
        return !frames.isEmpty() && frames.back().header.seq == seq ? &frames.back() : nullptr;
    }
    bool waitDisconnected(int timeoutMs = 10000) {
        return QTest::qWaitFor([this] { return disconnected; }, timeoutMs);
    }
    // The subprotocol the server selected.
    QString subprotocol() const { return socket_.subprotocol(); }
    // Drops the connection without a close handshake (as a killed client does).
    void abort() { socket_.abort(); }
    // Received text messages, each as compact JSON, joined.
    QString allText() const {
        QString all;
        for (const QJsonObject& t : texts) {
            all += QString::fromUtf8(QJsonDocument(t).toJson(QJsonDocument::Compact)) + "\n";
        }
        return all;
    }
    bool authenticate(const QString& token = kToken) {
        send({{"type", "auth"}, {"token", token}});
        return !waitForText("hello").isEmpty();
    }

    QList<QJsonObject> texts;
    QList<ReceivedFrame> frames;
    QList<ReceivedFrame> sliceFrames; // version 4: MPR slice frames (header.slice set)
    bool disconnected = false;
    std::uint64_t seq = 0;

private:
    QWebSocket socket_;
};

// Opens the server's only series at side x side with ct-bone (three view
// changes); its uid, empty when the server lists another number of series.
// The client must be authenticated.
inline QString openOnlySeries(RemoteTestClient& client, int side) {
    client.send({{"type", "list"}});
    const QJsonArray series = client.waitForText("series")["series"].toArray();
    if (series.size() != 1) {
        return {};
    }
    const QString uid = series[0].toObject()["uid"].toString();
    client.change({{"type", "open"}, {"series", uid}});
    client.change({{"type", "size"}, {"width", side}, {"height", side}});
    client.change({{"type", "tf"}, {"preset", "ct-bone"}});
    return uid;
}

} // namespace lucent::test
