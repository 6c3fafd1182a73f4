#pragma once
// What the files of ClientConnection share. Private to server/.

#include <QLoggingCategory>

namespace lucent::remote {

// "lucent.server.client": a client's connection, authentication, series and sessions.
Q_DECLARE_LOGGING_CATEGORY(lcClient)

} // namespace lucent::remote
