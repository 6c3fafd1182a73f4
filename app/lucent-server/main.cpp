// lucent-server: the headless render server. Serves the volumes of its study
// store and of --data over WebSocket (protocol v1, docs/protocol.md) to
// clients that present a token from --token-file; renders on one render
// thread with the GPU ray caster (EGL) or the CPU ray caster.
#include <QCommandLineParser>
#include <QCoreApplication>
#include <QFileInfo>
#include <QHostAddress>
#include <QTextStream>

#include <functional>

#include <memory>
#include <optional>

#include "server/DicomIntake.h"
#include "server/RenderServer.h"
#include "server/ServedSeries.h"

#if LUCENT_DISTRIBUTED
#include "render/distributed/DistributedSeries.h"
#include "render/distributed/MpiSession.h"
#include "server/DistributedFrameSource.h"
#endif

namespace {

constexpr int kUsage = 2;
constexpr int kBadInput = 3;

bool parseListen(const QString& text, QHostAddress* address, quint16* port) {
    const int colon = text.lastIndexOf(':');
    if (colon < 0) {
        return false;
    }
    bool ok = false;
    const uint p = text.mid(colon + 1).toUInt(&ok);
    QString host = text.left(colon);
    if (host == "localhost") {
        host = "127.0.0.1";
    }
    return ok && p <= 65535 && address->setAddress(host) && ((*port = quint16(p)), true);
}

// What --distributed changes in serve(): `ready` runs once everything is
// checked, just before the server is made; `frameSource` draws the frames.
struct ServeHooks {
    std::function<void()> ready;
    std::function<std::unique_ptr<lucent::remote::FrameSource>()> frameSource;
};

int serve(const QCommandLineParser& parser, const ServeHooks& hooks);

#if LUCENT_DISTRIBUTED

// Rank 0 serves; the other ranks wait for its verdict on the start ("go", or
// the status it exits with) and then follow its frames until it stops.
int serveDistributed(const QCommandLineParser& parser) {
    QTextStream err(stderr);
    std::optional<lucent::MpiSession> mpi;
    try {
        // Rank 0 starts in its main thread and renders on its render thread.
        mpi.emplace(lucent::MpiThreads::Serialised);
    } catch (const std::exception& e) {
        err << "lucent-server: --distributed: " << e.what() << "\n";
        return kBadInput;
    }
    const lucent::Communicator comm = lucent::Communicator::world();
    std::string verdict = "go";
    if (comm.rank() != 0) {
        comm.broadcast(verdict, 0);
        if (verdict != "go") {
            return std::stoi(verdict);
        }
        // The backend was checked by rank 0 before it said go.
        const lucent::RendererKind backend =
            lucent::parseRendererKind(parser.value("backend").toStdString());
        lucent::DistributedSeries(comm, backend).follow();
        return 0;
    }
    bool told = false;
    const ServeHooks hooks{
        [&] {
            comm.broadcast(verdict, 0);
            told = true;
        },
        [&]() -> std::unique_ptr<lucent::remote::FrameSource> {
            return std::make_unique<lucent::remote::DistributedFrameSource>(
                comm, lucent::parseRendererKind(parser.value("backend").toStdString()));
        }};
    const int status = serve(parser, hooks);
    if (!told) {
        verdict = std::to_string(status);
        comm.broadcast(verdict, 0);
    }
    return status;
}

#else

int serveDistributed(const QCommandLineParser&) {
    QTextStream(stderr) << "lucent-server: --distributed: this build has no distributed renderer "
                           "(configure with LUCENT_DISTRIBUTED=ON, which needs Open MPI and "
                           "IceT: packaging/install-deps.sh)\n";
    return kUsage;
}

#endif

} // namespace

int main(int argc, char** argv) {
    QCoreApplication app(argc, argv);
    QCoreApplication::setApplicationName("lucent-server");
    QCoreApplication::setApplicationVersion(LUCENT_VERSION);
    QCommandLineParser parser;
    parser.setApplicationDescription("Lucent render server (WebSocket protocol v1).");
    parser.addHelpOption();
    parser.addVersionOption();
    parser.addOptions({
        {"listen", "Address and port to listen on (port 0: any free one).", "HOST:PORT",
         "127.0.0.1:8765"},
        {"store", "Folder of the server's study store.", "DIR"},
        {"data", "Studies to serve besides the store's (DICOM folder or volume file).", "PATH"},
        {"token-file", "File of access tokens, one a line; only its owner may read it (0600).",
         "FILE"},
        {"tls-cert", "PEM certificate (chain): https:// and wss:// on the same port.", "FILE"},
        {"tls-key", "PEM private key of --tls-cert.", "FILE"},
        {"backend", "gl (EGL; the CPU where there is none) or cpu.", "NAME", "gl"},
        {"max-clients", "Clients served at once.", "N", "64"},
        {"max-sessions", "Teaching sessions at once.", "N", "16"},
        {"max-session-members", "Members of one teaching session, the presenter included.", "N",
         "64"},
        {"max-free-look",
         "Followers of one teaching session who may look on their own at once "
         "(0: none).",
         "N", "16"},
        {"keepalive", "Ping clients this often; drop one silent for three times as long.", "S",
         "20"},
        {"dicom-listen", "Receive C-STORE pushes into the store on this port (0: any free one).",
         "PORT"},
        {"aet", "AE title of the storage SCP (--dicom-listen).", "TITLE", "LUCENT"},
        {"arrival-quiet",
         "Pushed instances are served once none has come for this long (--dicom-listen).", "S",
         "2"},
        {"upload-limit", "Uploads (POST /studies) larger than this are refused.", "MIB", "512"},
        {"check", "Check the configuration, list the series, and exit."},
        {"distributed", "Render each frame with all the ranks of the MPI job this process is "
                        "part of (mpirun -n N lucent-server ... --distributed): rank 0 serves, "
                        "every rank renders its part of the volume, IceT composites."},
    });
    QTextStream err(stderr);
    if (!parser.parse(QCoreApplication::arguments())) {
        err << "lucent-server: " << parser.errorText() << "\n";
        return kUsage;
    }
    if (parser.isSet("help")) {
        parser.showHelp(0);
    }
    if (parser.isSet("version")) {
        parser.showVersion();
    }
    if (!parser.isSet("distributed")) {
        return serve(parser, ServeHooks{[] {}, {}});
    }
    return serveDistributed(parser);
}

namespace {

// The server's settings from the command line: 0, or the exit code after
// saying what is wrong.
struct ServeSettings {
    lucent::remote::ServerOptions options;
    int dicomPort = -1; // -1: no DICOM storage SCP
    double arrivalQuiet = 0.0;
};

int readSettings(const QCommandLineParser& parser, ServeSettings& settings, QTextStream& err) {
    if (!parseListen(parser.value("listen"), &settings.options.address, &settings.options.port)) {
        err << "lucent-server: --listen: '" << parser.value("listen") << "' is not HOST:PORT\n";
        return kUsage;
    }
    try {
        settings.options.backend = lucent::parseRendererKind(parser.value("backend").toStdString());
    } catch (const std::invalid_argument& e) {
        err << "lucent-server: --" << e.what() << "\n";
        return kUsage;
    }
    bool ok = false;
    settings.options.maxClients = parser.value("max-clients").toInt(&ok);
    if (!ok || settings.options.maxClients < 1) {
        err << "lucent-server: --max-clients must be a positive number\n";
        return kUsage;
    }
    settings.options.maxSessions = parser.value("max-sessions").toInt(&ok);
    if (!ok || settings.options.maxSessions < 1) {
        err << "lucent-server: --max-sessions must be a positive number\n";
        return kUsage;
    }
    settings.options.maxSessionMembers = parser.value("max-session-members").toInt(&ok);
    if (!ok || settings.options.maxSessionMembers < 2) {
        err << "lucent-server: --max-session-members must be a number from 2\n";
        return kUsage;
    }
    settings.options.maxFreeLook = parser.value("max-free-look").toInt(&ok);
    if (!ok || settings.options.maxFreeLook < 0 || settings.options.maxFreeLook > 4096) {
        err << "lucent-server: --max-free-look must be a number from 0 to 4096\n";
        return kUsage;
    }
    if (!parser.isSet("store") || !parser.isSet("token-file")) {
        err << "lucent-server: --store DIR and --token-file FILE are required\n";
        return kUsage;
    }
    settings.options.keepaliveSeconds = parser.value("keepalive").toInt(&ok);
    if (!ok || settings.options.keepaliveSeconds < 1 || settings.options.keepaliveSeconds > 3600) {
        err << "lucent-server: --keepalive must be a number of seconds from 1 to 3600\n";
        return kUsage;
    }
    const qint64 uploadLimitMib = parser.value("upload-limit").toLongLong(&ok);
    if (!ok || uploadLimitMib < 1 || uploadLimitMib > 16384) {
        err << "lucent-server: --upload-limit must be a number of MiB from 1 to 16384\n";
        return kUsage;
    }
    settings.options.uploadLimitBytes = uploadLimitMib << 20;
    if (parser.isSet("dicom-listen")) {
        settings.dicomPort = parser.value("dicom-listen").toInt(&ok);
        if (!ok || settings.dicomPort < 0 || settings.dicomPort > 65535) {
            err << "lucent-server: --dicom-listen: '" << parser.value("dicom-listen")
                << "' is not a port number (0 to 65535)\n";
            return kUsage;
        }
    }
    settings.arrivalQuiet = parser.value("arrival-quiet").toDouble(&ok);
    if (!ok || !(settings.arrivalQuiet >= 0.2 && settings.arrivalQuiet <= 600.0)) {
        err << "lucent-server: --arrival-quiet must be a number of seconds from 0.2 to 600\n";
        return kUsage;
    }
    if (parser.isSet("tls-cert") != parser.isSet("tls-key")) {
        err << "lucent-server: --tls-cert FILE and --tls-key FILE go together\n";
        return kUsage;
    }
    if (parser.isSet("tls-cert")) {
        settings.options.tls =
            lucent::remote::TlsFiles{parser.value("tls-cert"), parser.value("tls-key")};
        try {
            (void)lucent::remote::loadServerTls(
                *settings.options.tls); // fail before the slow start
        } catch (const std::exception& e) {
            err << "lucent-server: " << e.what() << "\n";
            return kBadInput;
        }
    }
    return 0;
}

// Everything after the command line: checks, the store, the server until it quits.
int serve(const QCommandLineParser& parser, const ServeHooks& hooks) {
    QTextStream err(stderr);
    ServeSettings settings;
    if (const int code = readSettings(parser, settings, err); code != 0) {
        return code;
    }
    lucent::remote::ServerOptions& options = settings.options;
    const int dicomPort = settings.dicomPort;
    const double arrivalQuiet = settings.arrivalQuiet;
    lucent::remote::ServedSeries stored;
    lucent::remote::ServedSeries fromData;
    try {
        options.tokens = lucent::remote::readTokenFile(parser.value("token-file"));
        options.storeDir = parser.value("store").toStdString();
        stored = lucent::remote::scanStoreSeries(options.storeDir);
        if (parser.isSet("data")) {
            fromData = lucent::remote::scanDataSeries(parser.value("data").toStdString());
        }
    } catch (const std::exception& e) {
        err << "lucent-server: " << e.what() << "\n";
        return kBadInput;
    }
    QTextStream out(stdout);
    // Counts only: series descriptions may identify a patient and stay out of logs.
    out << lucent::remote::mergeServedSeries(stored.volumes, fromData.volumes).size() << " series, "
        << stored.skippedFiles + fromData.skippedFiles << " file(s) skipped\n";
    out.flush();
    if (parser.isSet("check")) {
        return 0;
    }
    options.frameSource = hooks.frameSource;
    hooks.ready(); // from here the other ranks (--distributed) follow rank 0's frames
    lucent::remote::RenderServer server(options, std::move(stored.volumes),
                                        std::move(fromData.volumes));
    QString error;
    if (!server.listen(&error)) {
        err << "lucent-server: " << error << "\n";
        return kBadInput;
    }
    std::unique_ptr<lucent::remote::DicomIntake> intake;
    if (dicomPort >= 0) {
        try {
            intake = std::make_unique<lucent::remote::DicomIntake>(
                options.storeDir, parser.value("aet").toStdString(), dicomPort,
                int(arrivalQuiet * 1000), [&server] { server.rescanStore(); });
        } catch (const std::exception& e) {
            err << "lucent-server: --dicom-listen: " << e.what() << "\n";
            return kBadInput;
        }
        out << "DICOM storage SCP " << QString::fromStdString(intake->aeTitle()) << " on port "
            << intake->port() << "\n";
    }
    out << "browser client at " << (options.tls ? "https" : "http") << "://"
        << options.address.toString() << ":" << server.port() << "/\n";
    out << "listening on " << options.address.toString() << ":" << server.port() << "\n";
    out.flush();
    return QCoreApplication::exec();
}

} // namespace
