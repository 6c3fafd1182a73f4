// lucent-cli render PATH -o OUT.png [options]: a volume rendering to a PNG,
// with --stats and --repeat for benchmarks (see DESIGN.md's contract).
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFile>
#include <QJsonDocument>
#include <QTextStream>

#include <algorithm>

#include "CliCommand.h"
#include "QualityOption.h"
#include "RemoteRender.h"
#include "TerminalProgress.h"
#include "core/image/PngIO.h"
#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"
#include "core/quality/SceneCost.h"
#include "core/volume/BrickResidency.h"
#include "render/GlError.h"
#include "render/GpuRayCaster.h"
#include "render/OffscreenContext.h"

namespace lucent::cli {
namespace {

struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

double number(const QCommandLineParser& p, const QString& name, double fallback) {
    if (!p.isSet(name)) {
        return fallback;
    }
    bool ok = false;
    const double v = p.value(name).toDouble(&ok);
    if (!ok) {
        throw UsageError("--" + name.toStdString() + ": '" + p.value(name).toStdString() +
                         "' is not a number");
    }
    return v;
}

template <class E>
E choice(const QCommandLineParser& p, const QString& name, E fallback,
         std::initializer_list<std::pair<const char*, E>> options) {
    if (!p.isSet(name)) {
        return fallback;
    }
    std::string known;
    for (const auto& [key, value] : options) {
        if (p.value(name) == key) {
            return value;
        }
        known += (known.empty() ? "" : ", ") + std::string(key);
    }
    throw UsageError("--" + name.toStdString() + ": '" + p.value(name).toStdString() +
                     "' is not one of " + known);
}

RenderDescription describe(const QCommandLineParser& p, const Volume& volume) {
    RenderDescription d;
    d.volume = &volume;
    if (p.isSet("size")) {
        const QStringList wh = p.value("size").split('x');
        bool okW = false, okH = false;
        if (wh.size() == 2) {
            d.width = wh[0].toInt(&okW);
            d.height = wh[1].toInt(&okH);
        }
        if (!okW || !okH) {
            throw UsageError("--size: '" + p.value("size").toStdString() + "' is not WIDTHxHEIGHT");
        }
    }
    d.mode = choice(p, "mode", RenderMode::Dvr,
                    {{"dvr", RenderMode::Dvr},
                     {"mip", RenderMode::Mip},
                     {"minip", RenderMode::MinIp},
                     {"avg", RenderMode::Average},
                     {"iso", RenderMode::Isosurface}});
    d.isoValue = number(p, "iso", d.isoValue);
    d.camera.azimuth = number(p, "azimuth", 0.0);
    d.camera.elevation = number(p, "elevation", 0.0);
    d.camera.zoom = number(p, "zoom", 1.0);
    d.camera.distance = number(p, "distance", 0.0);
    d.camera.panRight = number(p, "pan-right", 0.0);
    d.camera.panUp = number(p, "pan-up", 0.0);
    SamplingSettings& s = d.sampling;
    s.step = number(p, "step", s.step);
    s.interpolation = choice(p, "interp", Interpolation::Linear,
                             {{"nearest", Interpolation::Nearest},
                              {"linear", Interpolation::Linear},
                              {"cubic", Interpolation::Cubic}});
    s.precision = choice(p, "precision", Precision::Float,
                         {{"float", Precision::Float}, {"double", Precision::Double}});
    s.classification = p.isSet("preclassify") ? Classification::Pre : Classification::Post;
    s.preintegrate = p.isSet("preintegrate");
    s.emptySpaceLeaping = !p.isSet("no-leaping");
    s.brickSize = static_cast<int>(number(p, "brick", s.brickSize));
    if (p.isSet("preset") && p.isSet("tf")) {
        throw UsageError("--preset and --tf exclude each other");
    }
    if (p.isSet("tf")) {
        d.transferFunction = readTransferFunction(p.value("tf").toStdString());
    } else {
        std::string preset = p.value("preset").toStdString();
        if (preset.empty()) {
            const bool ct = volume.modality == "CT";
            preset = !ct ? "mr-default" : d.mode == RenderMode::Dvr ? "ct-bone" : "ct-mip";
        }
        d.transferFunction = loadPreset(preset);
    }
    if (p.isSet("no-shading")) {
        d.transferFunction.shading.enabled = false;
    }
    return d;
}

} // namespace

int runRender(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription("Renders a volume to a PNG image.");
    parser.addPositionalArgument("PATH", "DICOM folder, file or DICOMDIR, or a volume file");
    parser.addOptions({
        {{"o", "output"}, "The PNG to write.", "OUT.png"},
        {"series", "Series id or UID (default: the largest volume).", "UID"},
        {"backend", "cpu, gl (an EGL context, no display needed) or ws://HOST:PORT (later).",
         "NAME", "cpu"},
        {"token", "Access token for a remote backend.", "T"},
        {"size", "Image size (default 512x512).", "WxH"},
        {"preset", "Transfer function preset (default ct-bone, ct-mip or mr-default).", "NAME"},
        {"tf", "Transfer function JSON file.", "FILE.json"},
        {"mode", "dvr, mip, minip, avg or iso.", "MODE"},
        {"iso", "Isosurface value (HU for CT).", "HU"},
        {"azimuth", "Turn about the head-foot axis, degrees.", "DEG"},
        {"elevation", "Turn about the left-right axis, degrees.", "DEG"},
        {"zoom", "1 fits the volume.", "F"},
        {"distance",
         "Eye to the point looked at, mm (default: fit the volume; less than the "
         "volume's radius puts the eye inside).",
         "MM"},
        {"pan-right", "Move the point looked at to the view's right, mm.", "MM"},
        {"pan-up", "Move the point looked at up in the view, mm.", "MM"},
        {"step", "Sampling step in voxels of the smallest spacing (default 0.5).", "VOXELS"},
        {"interp", "nearest, linear or cubic.", "NAME"},
        {"precision", "float (fast) or double (reference).", "NAME"},
        {"preclassify", "Classify voxels before interpolation."},
        {"preintegrate", "Pre-integrated transfer function."},
        {"no-shading", "Switch shading off."},
        {"no-leaping", "Switch empty-space leaping off."},
        {"brick", "Brick size in voxels (default 64).", "N"},
        {"gpu-budget", "GPU memory budget (GPU backend).", "MiB"},
        {"gradient-cache", "GPU: keep each brick's gradient for faster shading (the default)."},
        {"no-gradient-cache", "GPU: compute gradients from six fetches (less memory, slower)."},
        {"quality",
         "Sampling chosen from this volume's measured front: fast (50 ms a frame), balanced "
         "(250 ms), best (2000 ms) or a time per frame such as 120ms. Excludes --step, --interp, "
         "--preclassify, --preintegrate and --brick.",
         "LEVEL"},
        {"stats", "Print timing and sampling figures."},
        {"repeat", "Render N frames turning 5 degrees each; render_ms is their median.", "N"},
    });
    parser.addHelpOption();
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
    if (backend.startsWith("ws://") || backend.startsWith("wss://")) {
        return renderRemote(parser, err);
    }
    if (backend != "cpu" && backend != "gl") {
        err << "lucent-cli render: backend '" << backend
            << "' is not available (use --backend cpu, gl or ws://HOST:PORT)\n";
        return kUsage;
    }
    int repeat = 1;
    GpuOptions gpuOptions;
    std::optional<QualityRequest> quality;
    try {
        if (parser.isSet("quality")) {
            for (const char* chosen : {"step", "interp", "preclassify", "preintegrate", "brick"}) {
                if (parser.isSet(chosen)) {
                    throw UsageError(std::string("--quality chooses the sampling; leave out --") +
                                     chosen);
                }
            }
            try {
                quality = parseQualityRequest(parser.value("quality").toStdString());
            } catch (const std::invalid_argument& e) {
                throw UsageError(std::string("--") + e.what());
            }
        }
        repeat = static_cast<int>(number(parser, "repeat", 1));
        if (repeat < 1 || repeat > 10000) {
            throw UsageError("--repeat must be between 1 and 10000");
        }
        const double budget = number(parser, "gpu-budget", 0.0);
        if (!(budget >= 0.0) || budget > 1e7) {
            throw UsageError("--gpu-budget must be a number of MiB above 0");
        }
        gpuOptions.budgetBytes = std::size_t(budget * 1024.0 * 1024.0);
        if (parser.isSet("gradient-cache") && parser.isSet("no-gradient-cache")) {
            throw UsageError("--gradient-cache and --no-gradient-cache exclude each other");
        }
        gpuOptions.gradientCache = !parser.isSet("no-gradient-cache");
    } catch (const UsageError& e) {
        err << "lucent-cli render: " << e.what() << "\n";
        return kUsage;
    }

    QElapsedTimer timer;
    timer.start();
    Volume volume;
    const TerminalProgress progress;
    try {
        volume = loadPath(parser.positionalArguments()[0].toStdString(),
                          parser.value("series").toStdString(), progress.control());
        progress.finish();
    } catch (const std::exception& e) {
        progress.finish();
        err << "lucent-cli render: " << e.what() << "\n";
        return kBadInput;
    }
    const double loadMs = double(timer.nsecsElapsed()) / 1e6;

    try {
        RenderDescription desc = describe(parser, volume);
        desc.validate();
        // The GL backend needs an EGL context; without one the CPU renders, and says so.
        std::unique_ptr<OffscreenContext> context;
        std::unique_ptr<GpuRayCaster> gpu;
        std::string gpuExtra;
        if (backend == "gl") {
            try {
                context = OffscreenContext::create();
                gpu = std::make_unique<GpuRayCaster>(volume, gpuOptions);
            } catch (const GlError& e) {
                err << "lucent-cli render: the GL backend is not available (" << e.what()
                    << "); rendering on the CPU instead\n";
                gpu.reset();
                context.reset();
            }
        }
        std::unique_ptr<CpuRayCaster> cpu = gpu ? nullptr : std::make_unique<CpuRayCaster>(volume);
        std::string qualityStats;
        if (quality) {
            qualityStats = applyQuality(
                *quality, desc, gpu ? "gl" : "cpu",
                [&](const RenderDescription& d) {
                    return gpu ? gpu->render(d).frame : cpu->render(d);
                },
                err);
        }
        const RenderDescription firstDesc = desc; // the frame whose figures --stats prints
        std::vector<double> frames;
        RenderResult first;
        for (int n = 0; n < repeat; ++n) {
            timer.restart();
            RenderResult r;
            if (gpu) {
                GpuRenderResult g = gpu->render(desc);
                r = std::move(g.frame);
                if (n == 0) {
                    const GpuFrameStats& gs = g.gpu;
                    gpuExtra =
                        " backend=gl uploads=" + std::to_string(gs.bricksUploaded) +
                        " upload_mib=" +
                        QString::number(double(gs.bytesUploaded) / 1048576.0, 'f', 1)
                            .toStdString() +
                        " resident=" + std::to_string(gs.bricksResident) +
                        " pool_slots=" + std::to_string(gs.poolSlots) +
                        " budget_mib=" + std::to_string(gs.budgetBytes >> 20) +
                        " gradients=" + (gs.gradientsCached ? "cached" : "computed") +
                        " resident_mib=" +
                        QString::number(double(gs.residentBytes) / 1048576.0, 'f', 1)
                            .toStdString() +
                        " pool_mib=" +
                        QString::number(double(gs.poolBytes) / 1048576.0, 'f', 1).toStdString() +
                        " volume_mib=" +
                        QString::number(double(volume.byteCount()) / 1048576.0, 'f', 1)
                            .toStdString();
                    if (!gs.lodReason.empty()) {
                        err << "lucent-cli render: rendered from level " << r.stats.lod << ": "
                            << QString::fromStdString(gs.lodReason) << "\n";
                    }
                } else {
                    gpuExtra += n + 1 == repeat
                                    ? " uploads_after_first=" + std::to_string(g.gpu.bricksUploaded)
                                    : "";
                }
            } else {
                r = cpu->render(desc);
            }
            frames.push_back(double(timer.nsecsElapsed()) / 1e6);
            if (n == 0) {
                first = std::move(r);
            }
            desc.camera.azimuth += 5.0;
        }
        if (context) {
            gpuExtra += " renderer=\"" + context->description() + "\"";
        } else {
            gpuExtra = " backend=cpu";
        }
        writePng(first.image, parser.value("output").toStdString());
        if (parser.isSet("stats")) {
            const RenderStats& s = first.stats;
            QTextStream out(stdout);
            out << "load_ms=" << QString::number(loadMs, 'f', 1);
            if (repeat > 1) {
                out << " first_ms=" << QString::number(frames.front(), 'f', 1);
                frames.erase(frames.begin());
            }
            out << " render_ms=" << QString::number(median(frames), 'f', 1)
                << " samples=" << s.samples << " bricks_total=" << s.bricksTotal
                << " bricks_used=" << s.bricksUsed << " lod=" << s.lod
                << " brute_samples=" << bruteForceSamples(firstDesc) << " frames=" << repeat
                << QString::fromStdString(qualityStats) << QString::fromStdString(gpuExtra) << "\n";
        }
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
