#include "RemoteRender.h"

#include <QElapsedTimer>
#include <QEventLoop>
#include <QTimer>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "CliCommand.h"
#include "core/image/PngIO.h"
#include "core/scene/DefaultPreset.h"
#include "core/scene/RenderOptions.h"
#include "protocol/ProtocolMessages.h"
#include "render/RemoteRenderBackend.h"

namespace lucent::cli {
namespace {

constexpr int kTimeoutMs = 120000;

QString flagName(std::string_view flag) {
    return QString::fromUtf8(flag.data(), qsizetype(flag.size()));
}

// A render option of the table set on the command line, with its value as text.
struct SetOption {
    const RenderOption* option = nullptr;
    std::string text;
};

// The table's options that are set, each checked (applyRenderOption). Options
// the protocol does not carry are named on `err` and left out.
std::vector<SetOption> setOptions(const QCommandLineParser& p, QTextStream& err) {
    const QStringList given = p.optionNames();
    std::vector<SetOption> options;
    for (const RenderOption& o : renderOptions()) {
        const QString flag = flagName(o.cliFlag);
        if (o.cliFlag.empty() || !given.contains(flag)) {
            continue;
        }
        // The image size and clip box travel in their own messages; the others
        // in their table's.
        if (o.wireMessage.empty() && o.kind != OptionKind::Size && o.kind != OptionKind::Box) {
            err << "lucent-cli render: --" << flag
                << " is not sent to a remote backend (the server chooses it)\n";
            continue;
        }
        const std::string text =
            o.cliSets.empty() ? p.value(flag).toStdString() : std::string(o.cliSets);
        RenderDescription scratch;
        try {
            applyRenderOption(scratch, o, text);
        } catch (const std::invalid_argument& e) {
            throw UsageError("--" + flag.toStdString() + ": " + e.what());
        }
        options.push_back({&o, text});
    }
    return options;
}

// Flags of this computer's renderer, which a server does not take.
void nameLocalFlags(const QCommandLineParser& p, QTextStream& err) {
    const QStringList given = p.optionNames();
    const std::pair<const char*, const char*> local[] = {
        {"gpu-budget", "it sets this computer's GPU"},
        {"gradient-cache", "it sets this computer's GPU"},
        {"no-gradient-cache", "it sets this computer's GPU"},
        {"lod", "it sets this computer's GPU"},
        {"upload-cap", "it sets this computer's GPU"},
        {"quality", "it measures this computer's renderer on the volume; give --step and --interp"},
        {"repeat", "one still frame is rendered"},
        {"series", "PATH names the server's series"},
    };
    for (const auto& [flag, why] : local) {
        if (given.contains(flag)) {
            err << "lucent-cli render: --" << flag << " is not sent to a remote backend (" << why
                << ")\n";
        }
    }
}

// The description the flags ask for: the options, then the transfer function
// (whose default preset depends on the modality and the mode), then the options
// again, since shading lives in the transfer function.
RenderDescription describe(const QCommandLineParser& p, const std::vector<SetOption>& options,
                           const QString& modality) {
    RenderDescription d;
    for (const SetOption& o : options) {
        applyRenderOption(d, *o.option, o.text);
    }
    if (p.isSet("tf")) {
        d.transferFunction = readTransferFunction(p.value("tf").toStdString());
    } else {
        d.transferFunction =
            loadPreset(p.isSet("preset") ? p.value("preset").toStdString()
                                         : defaultPresetName(modality.toStdString(), d.mode));
    }
    for (const SetOption& o : options) {
        applyRenderOption(d, *o.option, o.text);
    }
    return d;
}

// What the server would refuse, refused here first: the view messages of the
// description, written and read back by the protocol's own writer and reader.
void checkSendable(const RenderDescription& d) {
    if (d.width < remote::kMinImageSide || d.height < remote::kMinImageSide ||
        d.width > remote::kMaxImageSide || d.height > remote::kMaxImageSide) {
        throw UsageError("--size: a remote backend renders " +
                         std::to_string(remote::kMinImageSide) + " to " +
                         std::to_string(remote::kMaxImageSide) + " pixels a side");
    }
    for (const remote::ClientMessage& m : remote::viewMessages(d)) {
        try {
            remote::parseClientMessage(remote::writeClientMessage(m));
        } catch (const remote::ProtocolError& e) {
            throw UsageError(std::string("a remote backend refuses this: ") + e.what());
        }
    }
}

// The still frame of `d` (made once the series is open, from its modality).
struct RemoteResult {
    std::optional<BackendFrame> frame;
    QString failure;
};

template <class Describe>
RemoteResult renderOnServer(RemoteRenderBackend& backend, const RemoteServerSettings& settings,
                            Describe describeFor) {
    RemoteResult result;
    QEventLoop loop;
    bool connected = false;
    const auto fail = [&](const QString& why) {
        if (result.failure.isEmpty() && !result.frame) {
            result.failure = why;
        }
        loop.quit();
    };
    QObject::connect(&backend, &RenderBackend::statusChanged, &loop,
                     [&](BackendStatus status, const QString& message) {
                         if (status == BackendStatus::Failed) {
                             fail(message);
                         } else if (status == BackendStatus::Connected) {
                             connected = true;
                             loop.quit();
                         }
                     });
    QObject::connect(&backend, &RenderBackend::frameFailed, &loop, fail);
    QObject::connect(&backend, &RenderBackend::frameReady, &loop, [&](const BackendFrame& f) {
        if (f.current && !f.interactive) {
            result.frame = f;
            loop.quit();
        }
    });
    QTimer::singleShot(kTimeoutMs, &loop, [&] {
        fail(QStringLiteral("%1: no frame within %2 s")
                 .arg(settings.url.toDisplayString(QUrl::RemoveUserInfo))
                 .arg(kTimeoutMs / 1000));
    });
    backend.connectTo(settings);
    if (backend.status() == BackendStatus::Failed) {
        fail(backend.statusMessage());
    }
    if (result.failure.isEmpty() && !connected) {
        loop.exec();
    }
    if (!result.failure.isEmpty()) {
        return result;
    }
    QString modality;
    for (const OfferedSeries& s : backend.offeredSeries()) {
        if (s.uid == backend.openSeries()) {
            modality = s.modality;
        }
    }
    backend.request(describeFor(modality), FrameOptions{});
    if (result.failure.isEmpty() && !result.frame) {
        loop.exec();
    }
    return result;
}

} // namespace

int renderRemote(const QCommandLineParser& p, QTextStream& err) {
    RemoteServerSettings settings;
    settings.url = QUrl(p.value("backend"));
    settings.token = p.value("token");
    settings.series = p.positionalArguments()[0];
    std::vector<SetOption> options;
    try {
        if (settings.token.isEmpty()) {
            throw UsageError("--backend ws:// needs --token");
        }
        if (p.isSet("preset") && p.isSet("tf")) {
            throw UsageError("--preset and --tf exclude each other");
        }
        options = setOptions(p, err);
        nameLocalFlags(p, err);
        // A bad transfer function, preset or value is our error, not the server's.
        checkSendable(describe(p, options, "CT"));
    } catch (const std::exception& e) {
        err << "lucent-cli render: " << e.what() << "\n";
        return kUsage;
    }
    QElapsedTimer timer;
    timer.start();
    RemoteRenderBackend backend;
    backend.setRetrying(false);
    const RemoteResult result = renderOnServer(
        backend, settings, [&](const QString& modality) { return describe(p, options, modality); });
    if (!result.frame) {
        err << "lucent-cli render: " << result.failure << "\n";
        return kNetwork;
    }
    try {
        writePng(result.frame->image, p.value("output").toStdString());
    } catch (const std::exception& e) {
        err << "lucent-cli render: cannot write " << p.value("output") << ": " << e.what() << "\n";
        return kBadInput;
    }
    if (p.isSet("stats")) {
        QTextStream(stdout) << "render_ms=" << QString::number(double(timer.elapsed()), 'f', 1)
                            << " server_render_ms="
                            << QString::number(result.frame->renderMs, 'f', 1)
                            << " backend=remote server_backend=\"" << backend.serverBackend()
                            << "\" server_protocol=" << backend.serverVersion() << "\n";
    }
    return kOk;
}

} // namespace lucent::cli
