#include "render/RemoteServerSettings.h"

#include <QObject>

namespace lucent {

QString RemoteServerSettings::problem() const {
    if (url.isEmpty()) {
        return QObject::tr("server URL: empty (e.g. ws://render-host:8765/)");
    }
    if (!url.isValid()) {
        return QObject::tr("server URL: %1").arg(url.errorString());
    }
    if (url.scheme() != "ws" && url.scheme() != "wss") {
        return QObject::tr("server URL: must start with ws:// or wss://, not %1://")
            .arg(url.scheme());
    }
    if (url.host().isEmpty()) {
        return QObject::tr("server URL: no host");
    }
    if (url.hasQuery() || !url.userInfo().isEmpty()) {
        return QObject::tr("server URL: no query or user part (the token goes in its own field)");
    }
    if (token.trimmed().isEmpty()) {
        return QObject::tr("token: empty (the server needs one of its --token-file lines)");
    }
    return {};
}

} // namespace lucent
