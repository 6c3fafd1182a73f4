#pragma once
// One still (lossless) frame from a lucent-server, for `lucent-cli render
// SERIES --backend ws://HOST:PORT --token T` (protocol v1, docs/protocol.md).

#include <QByteArray>
#include <QJsonObject>
#include <QString>
#include <QUrl>

#include <optional>
#include <stdexcept>

namespace lucent::cli {

// The server could not be reached, refused the token, or answered with an
// error: the message says which (and the server's error code).
class RemoteError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct RemoteStillRequest {
    QUrl url;
    QString token;
    QString series;
    int width = 512, height = 512;
    std::optional<QString> preset;
    std::optional<QJsonObject> transferFunction;
    std::optional<QString> mode;
    std::optional<double> iso;
    double azimuth = 0.0, elevation = 0.0, zoom = 1.0;
    // Sent only when set (servers before camera pan and distance refuse the fields).
    std::optional<double> distance, panRight, panUp; // mm; distance 0: fit the volume
};

struct RemoteStillFrame {
    QByteArray png;
    QString backend;     // the server's, from its hello
    double renderMs = 0; // the server's render time
};

// Throws RemoteError; gives up after timeoutMs.
RemoteStillFrame requestStillFrame(const RemoteStillRequest& request, int timeoutMs);

} // namespace lucent::cli
