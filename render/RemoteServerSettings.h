#pragma once

#include <QString>
#include <QUrl>

namespace lucent {

// Where the remote backend renders. The token goes in the first message,
// never in the URL or a log.
struct RemoteServerSettings {
    QUrl url;       // ws://HOST:PORT/ or wss://HOST:PORT/
    QString token;  // one of the server's --token-file lines
    QString series; // the series to open; empty: the loaded volume's Series UID

    // Empty when usable, else what is wrong, naming the field.
    QString problem() const;
    bool operator==(const RemoteServerSettings&) const = default;
};

} // namespace lucent
