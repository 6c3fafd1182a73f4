// lucent-server: the headless render server. This build checks its
// configuration and indexes the studies it would serve (--check); the render
// session protocol is not part of it yet.
#include <QCommandLineParser>
#include <QCoreApplication>
#include <QFileInfo>
#include <QTextStream>

#include "core/io/Catalog.h"

int main(int argc, char** argv) {
    QCoreApplication app(argc, argv);
    QCoreApplication::setApplicationName("lucent-server");
    QCoreApplication::setApplicationVersion(LUCENT_VERSION);
    QCommandLineParser parser;
    parser.setApplicationDescription("Lucent render server.");
    parser.addHelpOption();
    parser.addVersionOption();
    parser.addOptions({
        {"listen", "Address to listen on.", "HOST:PORT", "127.0.0.1:8765"},
        {"store", "Folder of the server's study store.", "DIR"},
        {"data", "Studies to index at start (DICOM folder or volume file).", "PATH"},
        {"token-file", "File holding the access token.", "FILE"},
        {"check", "Check the configuration, list the studies, and exit."},
    });
    QTextStream err(stderr);
    if (!parser.parse(QCoreApplication::arguments())) {
        err << "lucent-server: " << parser.errorText() << "\n";
        return 2;
    }
    if (parser.isSet("help")) {
        parser.showHelp(0);
    }
    if (parser.isSet("version")) {
        parser.showVersion();
    }
    if (parser.isSet("token-file") && !QFileInfo(parser.value("token-file")).isReadable()) {
        err << "lucent-server: token file " << parser.value("token-file") << " is not readable\n";
        return 3;
    }
    QTextStream out(stdout);
    if (parser.isSet("data")) {
        try {
            const lucent::Catalog catalog = lucent::scanPath(parser.value("data").toStdString());
            for (const lucent::SeriesEntry& e : catalog.series) {
                out << lucent::seriesKindName(e.kind) << " " << QString::fromStdString(e.id) << " "
                    << QString::fromStdString(e.description) << "\n";
            }
            out << catalog.series.size() << " series, " << catalog.skipped.size()
                << " file(s) skipped\n";
        } catch (const std::exception& e) {
            err << "lucent-server: " << e.what() << "\n";
            return 3;
        }
    }
    if (parser.isSet("check")) {
        return 0;
    }
    err << "lucent-server: this build has no render session protocol yet; use --check\n";
    return 1;
}
