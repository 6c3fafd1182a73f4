#pragma once
// For the remote tests: a real lucent-server process on a free loopback port
// (its own temporary store, token file and a synthetic CT volume), and a
// WebSocket client that records every message it receives.

#include <QDir>
#include <QElapsedTimer>
#include <QImage>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QTest>
#include <QWebSocket>
#include <QWebSocketHandshakeOptions>

#include <cmath>
#include <functional>
#include <memory>

#include "core/formats/MetaImage.h"
#include "core/image/Image.h"
#include "server/protocol/ProtocolMessages.h"

namespace lucent::test {

inline constexpr char kToken[] = "s3cret-token-for-tests";

// A 48 x 40 x 36 CT (HU, int16): air, an off-centre bone ball and a soft
// tissue block, so that the camera's turn shows in the image.
inline Volume syntheticCt() {
    VolumeGeometry g;
    g.dims = {48, 40, 36};
    g.spacing = {0.9, 0.9, 1.2};
    Volume v(g, VoxelType::Int16);
    v.modality = "CT";
    v.description = "synthetic";
    auto voxels = v.voxels<std::int16_t>();
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                const double ball = std::hypot(i - 30.0, j - 18.0, k - 20.0);
                const bool block = i > 6 && i < 22 && j > 8 && j < 30 && k > 5 && k < 28;
                const double hu = ball < 9.0 ? 1200.0 - 40.0 * ball
                                  : block    ? 60.0 + 3 * k
                                             : -1000.0;
                voxels[v.linearIndex(i, j, k)] = static_cast<std::int16_t>(hu);
            }
        }
    }
    return v;
}

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
            frames.append(
                {parsed.header, QByteArray(parsed.image.data(), qsizetype(parsed.image.size()))});
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
    bool disconnected = false;
    std::uint64_t seq = 0;

private:
    QWebSocket socket_;
};

class ServerProcess {
public:
    // Starts lucent-server on a free port with the synthetic CT as --data
    // (or `data` when given), and any further arguments.
    explicit ServerProcess(const QString& backend = "cpu", const QString& data = {},
                           const QStringList& extraArguments = {}) {
        QVERIFY(dir_.isValid());
        volumeFile_ = dir_.filePath("ct.mhd");
        writeMetaImage(syntheticCt(), volumeFile_.toStdString());
        QFile tokens(dir_.filePath("tokens"));
        QVERIFY(tokens.open(QIODevice::WriteOnly));
        tokens.write(QByteArray("# test tokens\n") + kToken + "\n");
        tokens.close();
        process_.setProcessChannelMode(QProcess::SeparateChannels);
        process_.start(QString(LUCENT_BIN_DIR) + "/lucent-server",
                       QStringList{"--listen", "127.0.0.1:0", "--store", dir_.filePath("store"),
                                   "--data", data.isEmpty() ? volumeFile_ : data, "--token-file",
                                   dir_.filePath("tokens"), "--backend", backend} +
                           extraArguments);
        QString out;
        (void)QTest::qWaitFor(
            [&] {
                out += QString::fromUtf8(process_.readAllStandardOutput());
                return out.contains("listening on") || process_.state() == QProcess::NotRunning;
            },
            60000);
        const qsizetype at = out.indexOf("listening on 127.0.0.1:");
        QVERIFY2(at >= 0, qPrintable("server did not start: " + out +
                                     QString::fromUtf8(process_.readAllStandardError())));
        port_ = quint16(out.mid(at + 23).trimmed().toUInt());
        QVERIFY(port_ > 0);
        startupOutput_ = out;
    }
    ~ServerProcess() {
        process_.terminate();
        if (!process_.waitForFinished(10000)) {
            process_.kill();
            process_.waitForFinished();
        }
    }
    quint16 port() const { return port_; }
    QString storeDir() const { return dir_.filePath("store"); }
    QString volumeFile() const { return volumeFile_; }
    QString tokenFile() const { return dir_.filePath("tokens"); }
    // What the server printed on stdout up to "listening on".
    const QString& startupOutput() const { return startupOutput_; }
    // What the server wrote to stderr so far (its log).
    QString log() { return log_ += QString::fromUtf8(process_.readAllStandardError()); }

private:
    QTemporaryDir dir_;
    QString volumeFile_;
    QProcess process_;
    quint16 port_ = 0;
    QString log_;
    QString startupOutput_;
};

} // namespace lucent::test
