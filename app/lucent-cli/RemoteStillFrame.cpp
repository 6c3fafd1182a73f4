#include "RemoteStillFrame.h"

#include <QEventLoop>
#include <QJsonDocument>
#include <QTimer>
#include <QWebSocket>

#include "protocol/ProtocolMessages.h"

namespace lucent::cli {

RemoteStillFrame requestStillFrame(const RemoteStillRequest& r, int timeoutMs) {
    QWebSocket socket;
    QEventLoop loop;
    QString failure;
    RemoteStillFrame result;
    std::uint64_t wanted = 0; // the seq of the last view message sent
    bool done = false;
    const auto fail = [&](const QString& why) {
        if (!done) {
            failure = why;
            done = true;
            loop.quit();
        }
    };
    const auto send = [&](const QJsonObject& message) {
        socket.sendTextMessage(
            QString::fromUtf8(QJsonDocument(message).toJson(QJsonDocument::Compact)));
    };
    const auto change = [&](const QJsonObject& message) {
        send(message);
        ++wanted;
    };
    QObject::connect(&socket, &QWebSocket::connected, [&] {
        send({{"type", "auth"}, {"token", r.token}});
    });
    QObject::connect(&socket, &QWebSocket::textMessageReceived, [&](const QString& text) {
        const QJsonObject m = QJsonDocument::fromJson(text.toUtf8()).object();
        const QString type = m["type"].toString();
        if (type == "error") {
            fail(QStringLiteral("the server refused (%1): %2")
                     .arg(m["code"].toString(), m["message"].toString()));
        } else if (type == "hello") {
            result.backend = m["backend"].toString();
            change({{"type", "open"}, {"series", r.series}});
            change({{"type", "size"}, {"width", r.width}, {"height", r.height}});
            if (r.preset) {
                change({{"type", "tf"}, {"preset", *r.preset}});
            } else if (r.transferFunction) {
                change({{"type", "tf"}, {"tf", *r.transferFunction}});
            }
            if (r.mode) {
                QJsonObject mode{{"type", "mode"}, {"mode", *r.mode}};
                if (r.iso) {
                    mode["iso"] = *r.iso;
                }
                change(mode);
            }
            QJsonObject camera{{"type", "camera"},
                               {"azimuth", r.azimuth},
                               {"elevation", r.elevation},
                               {"zoom", r.zoom}};
            for (const auto& [key, value] :
                 {std::pair{"distance", r.distance}, std::pair{"pan_right", r.panRight},
                  std::pair{"pan_up", r.panUp}}) {
                if (value) {
                    camera[QLatin1String(key)] = *value;
                }
            }
            change(camera);
            change({{"type", "quality"}, {"quality", "still"}});
        }
    });
    QObject::connect(&socket, &QWebSocket::binaryMessageReceived, [&](const QByteArray& b) {
        try {
            const auto frame =
                remote::parseFrameMessage(std::string_view(b.constData(), std::size_t(b.size())));
            if (frame.header.seq == wanted && frame.header.format == "png") {
                result.png = QByteArray(frame.image.data(), qsizetype(frame.image.size()));
                result.renderMs = frame.header.renderMs;
                done = true;
                loop.quit();
            }
        } catch (const std::exception& e) {
            fail(QStringLiteral("a frame that cannot be read: %1").arg(e.what()));
        }
    });
    QObject::connect(&socket, &QWebSocket::disconnected, [&] {
        fail(QStringLiteral("the server closed the connection (%1)").arg(socket.closeReason()));
    });
    // Qt 6.4 names the signal error (errorOccurred from 6.5).
    QObject::connect(&socket, qOverload<QAbstractSocket::SocketError>(&QWebSocket::error),
                     [&](QAbstractSocket::SocketError) { fail(socket.errorString()); });
    QTimer::singleShot(timeoutMs, &loop,
                       [&] { fail(QStringLiteral("no frame within %1 s").arg(timeoutMs / 1000)); });
    socket.open(r.url);
    if (!done) {
        loop.exec();
    }
    socket.abort();
    if (!failure.isEmpty()) {
        throw RemoteError(r.url.toString().toStdString() + ": " + failure.toStdString());
    }
    return result;
}

} // namespace lucent::cli
