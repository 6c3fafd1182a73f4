#pragma once
// lucent-cli render SERIES --backend ws://HOST:PORT --token T [render options]:
// one still frame of a series a lucent-server holds, through RemoteRenderBackend
// (the client the 3D view uses), with every render option the protocol carries.

#include <QCommandLineParser>
#include <QTextStream>

namespace lucent::cli {

// Exit 0, 2 (usage), 3 (the image cannot be written) or 4 (the server or the
// network failed, or the server cannot honour a setting).
int renderRemote(const QCommandLineParser& parser, QTextStream& err);

} // namespace lucent::cli
