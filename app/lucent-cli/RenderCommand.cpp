// lucent-cli render PATH -o OUT.png [options]: a volume rendering to a PNG,
// with --stats and --repeat for benchmarks (see DESIGN.md's contract).
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFile>
#include <QJsonDocument>
#include <QTextStream>

#include <algorithm>

#include "CliCommand.h"
#include "DistributedRender.h"
#include "FrameSeries.h"
#include "OverlayFlags.h"
#include "QualityOption.h"
#include "RemoteRender.h"
#include "RenderFlags.h"
#include "TerminalProgress.h"
#include "core/fusion/OverlayResampler.h"
#include "core/image/PngIO.h"
#include "core/io/Catalog.h"
#include "core/quality/SceneCost.h"
#include "core/volume/BrickResidency.h"
#include "render/GlError.h"
#include "render/RenderDevice.h"

namespace lucent::cli {
namespace {

std::string mib(std::size_t bytes) {
    return QString::number(double(bytes) / 1048576.0, 'f', 1).toStdString();
}

void addRenderOptions(QCommandLineParser& parser) {
    parser.setApplicationDescription("Renders a volume to a PNG image.");
    parser.addPositionalArgument("PATH", "DICOM folder, file or DICOMDIR, or a volume file");
    parser.addOptions({
        {{"o", "output"}, "The PNG to write.", "OUT.png"},
        {"series", "Series id or UID (default: the largest volume).", "UID"},
        {"backend", "cpu, gl (an EGL context, no display needed) or ws://HOST:PORT.", "NAME",
         "cpu"},
        {"token", "Access token for a remote backend.", "T"},
        {"preset", "Transfer function preset (default ct-bone, ct-mip or mr-default).", "NAME"},
        {"tf", "Transfer function JSON file.", "FILE.json"},
        {"gpu-budget", "GPU memory budget (GPU backend).", "MiB"},
        {"gradient-cache",
         "GPU: keep each brick's gradient for faster shading whatever memory it takes (by "
         "default only while the bricks stay within twice the volume's bytes)."},
        {"no-gradient-cache", "GPU: compute gradients from six fetches (less memory, slower)."},
        {"lod",
         "GPU, under a budget too small for level 0: per-brick (each brick as fine as the budget "
         "allows, those near the eye, in focus and showing most first; the default) or uniform "
         "(the whole volume at one level).",
         "POLICY", "per-brick"},
        {"upload-cap",
         "GPU: MiB a frame may upload beyond what it must show; bricks over it are shown from a "
         "coarser level while they stream in (stats: pending).",
         "MiB"},
        {"quality",
         "Sampling chosen from this volume's measured front: fast (50 ms a frame), balanced "
         "(250 ms), best (2000 ms) or a time per frame such as 120ms. Excludes --step, --interp, "
         "--preclassify, --preintegrate and --brick.",
         "LEVEL"},
        {"stats", "Print timing and sampling figures."},
        {"repeat", "Render N frames turning 5 degrees each; render_ms is their median.", "N"},
        {"distributed", "Under mpirun: every rank renders its part of the volume, IceT "
                        "composites, rank 0 writes OUT.png (docs/distributed.md)."},
    });
    addRenderFlags(parser);
    addOverlayFlags(parser);
    parser.addHelpOption();
}

// How a local render runs: flags beyond the description's. parseLocalRun
// throws UsageError naming a flag that is wrong.
struct LocalRun {
    RendererKind kind = RendererKind::Cpu;
    int repeat = 1;
    GpuOptions gpu;
    std::optional<QualityRequest> quality;
};

LocalRun parseLocalRun(const QCommandLineParser& parser) {
    LocalRun run;
    const QString backend = parser.value("backend");
    try {
        run.kind = parseRendererKind(backend.toStdString());
    } catch (const std::invalid_argument&) {
        throw UsageError("backend '" + backend.toStdString() +
                         "' is not available (use --backend cpu, gl or ws://HOST:PORT)");
    }
    if (parser.isSet("quality")) {
        for (const char* chosen : {"step", "interp", "preclassify", "preintegrate", "brick"}) {
            if (parser.isSet(chosen)) {
                throw UsageError(std::string("--quality chooses the sampling; leave out --") +
                                 chosen);
            }
        }
        try {
            run.quality = parseQualityRequest(parser.value("quality").toStdString());
        } catch (const std::invalid_argument& e) {
            throw UsageError(std::string("--") + e.what());
        }
    }
    run.repeat = static_cast<int>(numberFlag(parser, "repeat", 1));
    if (run.repeat < 1 || run.repeat > 10000) {
        throw UsageError("--repeat must be between 1 and 10000");
    }
    const double budget = numberFlag(parser, "gpu-budget", 0.0);
    if (!(budget >= 0.0) || budget > 1e7) {
        throw UsageError("--gpu-budget must be a number of MiB above 0");
    }
    run.gpu.budgetBytes = std::size_t(budget * 1024.0 * 1024.0);
    if (parser.isSet("gradient-cache") && parser.isSet("no-gradient-cache")) {
        throw UsageError("--gradient-cache and --no-gradient-cache exclude each other");
    }
    run.gpu.gradientCache = !parser.isSet("no-gradient-cache");
    if (parser.isSet("gradient-cache")) {
        run.gpu.gradientCacheShare = 0.0; // no limit
    }
    const QString lod = parser.value("lod");
    if (lod != "per-brick" && lod != "uniform") {
        throw UsageError("--lod must be per-brick or uniform, not '" + lod.toStdString() + "'");
    }
    run.gpu.lodPolicy = lod == "uniform" ? LodPolicy::Uniform : LodPolicy::PerBrick;
    const double cap = numberFlag(parser, "upload-cap", 0.0);
    if (!(cap >= 0.0) || cap > 1e7) {
        throw UsageError("--upload-cap must be a number of MiB, 0 for none");
    }
    run.gpu.uploadBytesPerFrame = std::size_t(cap * 1024.0 * 1024.0);
    return run;
}

// The --stats line: the first frame's figures, its times from the last frame (no uploads).
void printStats(double loadMs, const FrameSeries& series, const RenderDescription& firstDesc,
                int repeat, const std::string& qualityStats, const Renderer& renderer,
                const Volume& volume) {
    FrameDetails details = series.firstDetails;
    for (const auto& [key, value] : series.lastDetails) {
        if (key == "uploads" && repeat > 1) {
            details.emplace_back("uploads_after_first", value);
        }
        for (auto& [firstKey, firstValue] : details) {
            if (firstKey == key && key.ends_with("_ms")) {
                firstValue = value;
            }
        }
    }
    QTextStream out(stdout);
    out << seriesStats(loadMs, series) << " brute_samples=" << bruteForceSamples(firstDesc)
        << " frames=" << repeat << QString::fromStdString(qualityStats)
        << " backend=" << QString::fromStdString(renderer.backend());
    for (const auto& [key, value] : details) {
        out << " " << QString::fromStdString(key) << "=" << QString::fromStdString(value);
    }
    if (renderer.backend() == "gl") {
        out << " volume_mib=" << QString::fromStdString(mib(volume.byteCount())) << " renderer=\""
            << QString::fromStdString(renderer.device()) << "\"";
    }
    out << "\n";
}

// Renders the loaded volume (and overlay) on this machine and writes the PNG.
void renderHere(const QCommandLineParser& parser, const LocalRun& run, const Volume& volume,
                const std::optional<Volume>& overlay, double loadMs, QTextStream& err) {
    RenderDescription desc = describeFromFlags(parser, volume);
    if (overlay) {
        desc.overlay.volume = &*overlay;
        resolveOverlayWindow(desc.overlay);
    }
    desc.validate();
    // The GL backend needs an EGL context; without one the CPU renders, and says so.
    const std::unique_ptr<RenderDevice> device = RenderDevice::open(run.kind);
    RenderDevice::Opened opened = device->openRenderer(volume, run.gpu);
    for (const std::string& reason : {device->fallbackReason(), opened.fallbackReason}) {
        if (!reason.empty()) {
            err << "lucent-cli render: " << QString::fromStdString(reason)
                << "; rendering on the CPU instead\n";
        }
    }
    Renderer& renderer = *opened.renderer;
    std::string qualityStats;
    if (run.quality) {
        qualityStats = applyQuality(
            *run.quality, desc, renderer.backend(),
            [&](const RenderDescription& d) { return renderer.render(d); }, err);
    }
    const RenderDescription firstDesc = desc; // the frame whose figures --stats prints
    const FrameSeries series = renderFrames(renderer, desc, run.repeat);
    const RenderResult& first = series.first;
    if (!first.stats.lodReason.empty()) {
        err << "lucent-cli render: rendered from level " << first.stats.lod << ": "
            << QString::fromStdString(first.stats.lodReason) << "\n";
    }
    writePng(first.image, parser.value("output").toStdString());
    if (parser.isSet("stats")) {
        printStats(loadMs, series, firstDesc, run.repeat, qualityStats, renderer, volume);
    }
}

} // namespace

int runRender(const QStringList& args) {
    QCommandLineParser parser;
    addRenderOptions(parser);
    QTextStream err(stderr);
    if (!parser.parse(args)) {
        err << "lucent-cli render: " << parser.errorText() << "\n";
        return kUsage;
    }
    if (parser.isSet("help")) {
        QTextStream(stdout) << parser.helpText();
        return kOk;
    }
    if (parser.positionalArguments().size() != 1 || !parser.isSet("output")) {
        err << "lucent-cli render: expected PATH and -o OUT.png\n";
        return kUsage;
    }
    const QString backend = parser.value("backend");
    if (const std::string why = renderOverlayUsage(parser); !why.empty()) {
        err << "lucent-cli render: " << QString::fromStdString(why) << "\n";
        return kUsage;
    }
    if (parser.isSet("distributed")) {
        return runDistributedRender(parser);
    }
    if (backend.startsWith("ws://") || backend.startsWith("wss://")) {
        return renderRemote(parser, err);
    }
    LocalRun run;
    try {
        run = parseLocalRun(parser);
    } catch (const UsageError& e) {
        err << "lucent-cli render: " << e.what() << "\n";
        return kUsage;
    }

    QElapsedTimer timer;
    timer.start();
    Volume volume;
    std::optional<Volume> overlay; // on the volume's grid
    const TerminalProgress progress;
    try {
        volume = loadPath(parser.positionalArguments()[0].toStdString(),
                          parser.value("series").toStdString(), progress.control());
        overlay = loadOverlay(parser, volume, kOverlayFill, progress.control());
        progress.finish();
    } catch (const UsageError& e) {
        progress.finish();
        err << "lucent-cli render: " << e.what() << "\n";
        return kUsage;
    } catch (const std::exception& e) {
        progress.finish();
        err << "lucent-cli render: " << e.what() << "\n";
        return kBadInput;
    }
    const double loadMs = double(timer.nsecsElapsed()) / 1e6;

    try {
        renderHere(parser, run, volume, overlay, loadMs, err);
    } catch (const UsageError& e) {
        err << "lucent-cli render: " << e.what() << "\n";
        return kUsage;
    } catch (const std::invalid_argument& e) {
        err << "lucent-cli render: " << e.what() << "\n";
        return kUsage;
    } catch (const BudgetError& e) {
        err << "lucent-cli render: " << e.what() << "\n";
        return kBadInput;
    } catch (const GlError& e) {
        err << "lucent-cli render: GL: " << e.what() << "\n";
        return kBadInput;
    } catch (const std::exception& e) {
        err << "lucent-cli render: " << e.what() << "\n";
        return kBadInput;
    }
    return kOk;
}

} // namespace lucent::cli
