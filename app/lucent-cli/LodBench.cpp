// lucent-cli bench lod PATH: what a GPU memory budget costs in image quality.
// For each budget, the GL renderer draws the volume with per-brick levels and
// with one level for the whole volume; each frame is measured against the
// frame drawn without a budget (PSNR, SSIM), with the bytes it kept resident.
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QPainterPath>
#include <QTextStream>

#include <algorithm>
#include <cmath>
#include <map>

#include "BenchSetup.h"
#include "CliCommand.h"
#include "PlotCanvas.h"
#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "core/scene/RenderOptions.h"
#include "render/GlError.h"
#include "render/RenderDevice.h"

namespace lucent::cli {

namespace {

struct LodPoint {
    double budgetMib = 0.0;
    std::string policy;
    double psnrDb = 0.0, ssim = 0.0, ms = 0.0;
    std::map<std::string, std::string> details; // the frame's resident_mib, levels, ...
};

std::string detail(const LodPoint& p, const std::string& key) {
    const auto it = p.details.find(key);
    return it == p.details.end() ? "" : it->second;
}

// PSNR against the budget (log 2), a line per policy.
void writeLodPlot(const std::vector<LodPoint>& points, const QString& path, const QString& title) {
    PlotAxes axes;
    axes.base = 2.0;
    axes.xLo = 1e300;
    axes.xHi = 0.0;
    double dbLo = 1e300, dbHi = 0.0;
    for (const LodPoint& q : points) {
        axes.xLo = std::min(axes.xLo, q.budgetMib);
        axes.xHi = std::max(axes.xHi, q.budgetMib);
        if (std::isfinite(q.psnrDb)) {
            dbLo = std::min(dbLo, q.psnrDb);
            dbHi = std::max(dbHi, q.psnrDb);
        }
    }
    axes.xUnit = " MiB";
    axes.yMin = std::floor(dbLo / 5.0) * 5.0;
    axes.yMax = std::ceil(dbHi / 5.0) * 5.0 + 5.0;
    axes.yStep = 5.0;
    axes.title = title;
    axes.caption =
        "GPU budget (log 2)   |   red: per-brick levels   |   blue: one level for the volume";
    axes.yLabel = "PSNR (dB) vs no budget";
    PlotCanvas canvas(axes);
    QPainter& p = canvas.painter();
    for (const auto& [policy, colour] : {std::pair{std::string("per-brick"), QColor(200, 30, 30)},
                                         std::pair{std::string("uniform"), QColor(40, 80, 200)}}) {
        QPainterPath line;
        bool first = true;
        for (const LodPoint& q : points) {
            if (q.policy != policy) {
                continue;
            }
            const QPointF at(canvas.x(q.budgetMib), canvas.y(q.psnrDb));
            first ? line.moveTo(at) : line.lineTo(at);
            first = false;
            p.setPen(Qt::NoPen);
            p.setBrush(colour);
            p.drawEllipse(at, 4, 4);
        }
        p.setPen(QPen(colour, 2));
        p.setBrush(Qt::NoBrush);
        p.drawPath(line);
    }
    canvas.save(path);
}

} // namespace

int runLodBench(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription("bench lod PATH: PSNR against the frame without a budget, "
                                     "for each GPU budget, per-brick levels and one level.");
    parser.addPositionalArgument("lod", "The bench to run (lod).");
    parser.addPositionalArgument("PATH", "DICOM folder, file or DICOMDIR, or a volume file");
    addVolumeBenchOptions(parser);
    parser.addOptions({
        {"budgets", "Budgets in MiB (default 1,2,4,8,16,32,64).", "LIST", "1,2,4,8,16,32,64"},
        {"plot", "Draw PSNR against the budget.", "OUT.png"},
    });
    parser.addHelpOption();
    QTextStream err(stderr), out(stdout);
    if (!parser.parse(args)) {
        err << "lucent-cli bench: " << parser.errorText() << "\n";
        return kUsage;
    }
    const QStringList pos = parser.positionalArguments();
    std::vector<double> budgets;
    bool ok = pos.size() == 2;
    for (const QString& b : parser.value("budgets").split(',')) {
        bool good = false;
        budgets.push_back(b.toDouble(&good));
        ok = ok && good && budgets.back() > 0.0;
    }
    int width = 0, height = 0;
    try {
        std::tie(width, height) = parseImageSize(parser.value("size").toStdString());
    } catch (const std::invalid_argument&) {
        ok = false;
    }
    if (!ok) {
        err << "lucent-cli bench: expected 'lod PATH' with --budgets of MiB above 0 and a --size\n";
        return kUsage;
    }
    try {
        const Volume volume = loadPath(pos[1].toStdString(), parser.value("series").toStdString());
        RenderDescription d;
        d.volume = &volume;
        d.width = width;
        d.height = height;
        const std::string preset = benchPreset(parser, volume, d.mode);
        d.transferFunction = loadPreset(preset);
        const std::unique_ptr<RenderDevice> device = RenderDevice::open(RendererKind::Gl);
        if (!device->fallbackReason().empty()) {
            throw GlError(device->fallbackReason());
        }
        const ImageRGBA8 full = device->openRenderer(volume).renderer->render(d).image;
        std::vector<LodPoint> points;
        for (const double mib : budgets) {
            for (const LodPolicy policy : {LodPolicy::PerBrick, LodPolicy::Uniform}) {
                GpuOptions options;
                options.budgetBytes = std::size_t(mib * 1048576.0);
                options.lodPolicy = policy;
                LodPoint p;
                p.budgetMib = mib;
                p.policy = policy == LodPolicy::PerBrick ? "per-brick" : "uniform";
                try {
                    const RenderDevice::Opened r = device->openRenderer(volume, options);
                    r.renderer->render(d); // uploads
                    QElapsedTimer timer;
                    timer.start();
                    const ImageRGBA8 image = r.renderer->render(d).image;
                    p.ms = double(timer.nsecsElapsed()) / 1e6;
                    p.psnrDb = psnr(image, full);
                    p.ssim = ssim(image, full);
                    for (const auto& [key, value] : r.renderer->frameDetails()) {
                        p.details[key] = value;
                    }
                } catch (const std::exception& e) { // a budget below the coarsest level
                    err << "lucent-cli bench: " << mib << " MiB, " << p.policy.c_str() << ": "
                        << e.what() << "\n";
                    continue;
                }
                points.push_back(p);
            }
        }
        const QString header = "budget_mib,policy,psnr_db,ssim,ms,resident_mib,pool_mib,levels\n";
        QString rows;
        for (const LodPoint& p : points) {
            rows += QStringLiteral("%1,%2,%3,%4,%5,%6,%7,\"%8\"\n")
                        .arg(p.budgetMib)
                        .arg(QString::fromStdString(p.policy))
                        .arg(p.psnrDb, 0, 'f', 2)
                        .arg(p.ssim, 0, 'f', 4)
                        .arg(p.ms, 0, 'f', 1)
                        .arg(QString::fromStdString(detail(p, "resident_mib")))
                        .arg(QString::fromStdString(detail(p, "pool_mib")))
                        .arg(QString::fromStdString(detail(p, "levels")));
        }
        writeBenchCsv(parser, header + rows);
        if (parser.isSet("plot") && !points.empty()) {
            writeLodPlot(points, parser.value("plot"),
                         benchPlotTitle(pos[1], volume, preset, width, height, "gl"));
        }
        out << header << rows;
    } catch (const std::exception& e) {
        err << "lucent-cli bench: " << e.what() << "\n";
        return kBadInput;
    }
    return kOk;
}

} // namespace lucent::cli
