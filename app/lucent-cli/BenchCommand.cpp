// lucent-cli bench quality PATH: the speed/accuracy sweep (issue "measure the
// trade"): time, samples, PSNR and SSIM of every sampling setting against the
// reference, the front, a CSV and a plot.
#include <QCommandLineParser>
#include <QTextStream>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <tuple>
#include <vector>

#include "BenchSetup.h"
#include "CliCommand.h"
#include "QualityPlot.h"
#include "TerminalProgress.h"
#include "core/io/Catalog.h"
#include "core/quality/QualityFront.h"
#include "core/raycast/CpuRayCaster.h"
#include "core/scene/RenderOptions.h"
#include "render/GlError.h"
#include "render/RenderDevice.h"

namespace lucent::cli {
namespace {

QString csvLine(const QualityPoint& p) {
    return QString::fromStdString(qualityCsvRow(p));
}

// bench quality's flags beyond the volume's; nullopt where one is wrong.
struct SweepFlags {
    QString backend;
    int width = 0, height = 0, frames = 0;
    std::vector<double> steps;
    std::vector<int> bricks;
};

std::optional<SweepFlags> parseSweepFlags(const QCommandLineParser& parser) {
    SweepFlags f;
    f.backend = parser.value("backend");
    bool okSize = true, okF = false;
    try {
        std::tie(f.width, f.height) = parseImageSize(parser.value("size").toStdString());
    } catch (const std::invalid_argument&) {
        okSize = false;
    }
    f.frames = parser.value("frames").toInt(&okF);
    bool listsOk = true;
    for (const QString& s : parser.value("steps").split(',')) {
        bool ok = false;
        f.steps.push_back(s.toDouble(&ok));
        listsOk = listsOk && ok && f.steps.back() > 0.0;
    }
    for (const QString& s : parser.value("bricks").split(',')) {
        bool ok = false;
        f.bricks.push_back(s.toInt(&ok));
        listsOk = listsOk && ok && f.bricks.back() > 0;
    }
    if (!okSize || !okF || f.frames < 1 || !listsOk || (f.backend != "cpu" && f.backend != "gl")) {
        return std::nullopt;
    }
    return f;
}

// The front, fastest first, as CSV rows under the header.
void printFront(QTextStream& out, const std::vector<QualityPoint>& points, const QString& header,
                const QString& backend) {
    std::vector<QualityPoint> front;
    std::copy_if(points.begin(), points.end(), std::back_inserter(front),
                 [](const QualityPoint& p) { return p.pareto; });
    std::sort(front.begin(), front.end(),
              [](const QualityPoint& a, const QualityPoint& b) { return a.ms < b.ms; });
    out << "front (" << front.size() << " of " << points.size() << " settings, " << backend
        << "):\n"
        << header;
    for (const QualityPoint& p : front) {
        out << csvLine(p);
    }
}

// Every setting of the sweep timed on the flags' backend and compared with the
// CPU reference; the CSV, the plot and the front.
void sweep(const QCommandLineParser& parser, const SweepFlags& f, const Volume& volume,
           const QString& path, QTextStream& out, QTextStream& err) {
    RenderDescription base;
    base.volume = &volume;
    base.width = f.width;
    base.height = f.height;
    const std::string preset = benchPreset(parser, volume, base.mode);
    base.transferFunction = loadPreset(preset);

    CpuRayCaster cpu(volume); // the reference, and what a CPU bench measures
    Renderer* measured = &cpu;
    RenderDevice::Opened opened;
    if (parseRendererKind(f.backend.toStdString()) == RendererKind::Gl) {
        // A bench of the GL backend measures GL or nothing: no silent CPU fallback.
        const std::unique_ptr<RenderDevice> device = RenderDevice::open(RendererKind::Gl);
        opened = device->openRenderer(volume);
        for (const std::string& reason : {device->fallbackReason(), opened.fallbackReason}) {
            if (!reason.empty()) {
                throw GlError(reason);
            }
        }
        measured = opened.renderer.get();
    }
    const std::function<RenderResult(const RenderDescription&)> render =
        [&](const RenderDescription& d) { return measured->render(d); };

    const std::vector<QualityPoint> points = measureQuality(
        base, qualitySweep(f.steps, f.bricks), render,
        [&](const RenderDescription& d) { return cpu.render(d); }, f.frames,
        [&](std::size_t, std::size_t) { err << "." << Qt::flush; });
    err << "\n";
    const QString header = QString::fromStdString(qualityCsvHeader()) + "\n";
    QString csv = header;
    for (const QualityPoint& p : points) {
        csv += csvLine(p);
    }
    writeBenchCsv(parser, csv);
    if (parser.isSet("plot")) {
        writeQualityPlot(points, parser.value("plot"),
                         benchPlotTitle(path, volume, preset, f.width, f.height, f.backend));
    }
    printFront(out, points, header, f.backend);
}

} // namespace

int runBench(const QStringList& args) {
    if (args.size() > 1 && args[1] == "lod") {
        return runLodBench(args);
    }
    if (args.size() > 1 && args[1] == "interactive") {
        return runInteractiveBench(args);
    }
    QCommandLineParser parser;
    parser.setApplicationDescription("bench quality PATH: time against accuracy for every sampling "
                                     "setting, measured against the reference (double, tricubic, "
                                     "step 1/16 voxel, no early termination).");
    parser.addPositionalArgument("quality", "The bench to run (quality).");
    parser.addPositionalArgument("PATH", "DICOM folder, file or DICOMDIR, or a volume file");
    addVolumeBenchOptions(parser);
    parser.addOptions({
        {"backend", "cpu or gl.", "NAME", "cpu"},
        {"plot", "Draw time against PSNR with the front.", "OUT.png"},
        {"frames", "Frames timed per setting (median; default 3).", "N", "3"},
        {"steps", "Steps in voxels (default 2,1,0.5,0.25,0.125).", "LIST", "2,1,0.5,0.25,0.125"},
        {"bricks", "Brick sizes (default 64).", "LIST", "64"},
    });
    parser.addHelpOption();
    QTextStream err(stderr), out(stdout);
    if (!parser.parse(args)) {
        err << "lucent-cli bench: " << parser.errorText() << "\n";
        return kUsage;
    }
    if (parser.isSet("help")) {
        out << parser.helpText();
        return kOk;
    }
    const QStringList pos = parser.positionalArguments();
    if (pos.size() != 2 || pos[0] != "quality") {
        err << "lucent-cli bench: expected 'quality PATH'\n";
        return kUsage;
    }
    const std::optional<SweepFlags> flags = parseSweepFlags(parser);
    if (!flags) {
        err << "lucent-cli bench: bad --size, --frames, --steps, --bricks or --backend\n";
        return kUsage;
    }

    Volume volume;
    try {
        const TerminalProgress progress;
        volume = loadPath(pos[1].toStdString(), parser.value("series").toStdString(),
                          progress.control());
        progress.finish();
    } catch (const std::exception& e) {
        err << "lucent-cli bench: " << e.what() << "\n";
        return kBadInput;
    }
    try {
        sweep(parser, *flags, volume, pos[1], out, err);
    } catch (const GlError& e) {
        err << "lucent-cli bench: GL: " << e.what() << "\n";
        return kBadInput;
    } catch (const std::exception& e) {
        err << "lucent-cli bench: " << e.what() << "\n";
        return kBadInput;
    }
    return kOk;
}

} // namespace lucent::cli
