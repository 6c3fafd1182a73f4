// lucent-cli bench lod PATH: what a GPU memory budget costs in image quality.
// For each budget, the GL renderer draws the volume with per-brick levels and
// with one level for the whole volume; each frame is measured against the
// frame drawn without a budget (PSNR, SSIM), with the bytes it kept resident.
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QFile>
#include <QImage>
#include <QPainter>
#include <QPainterPath>
#include <QTextStream>

#include <algorithm>
#include <cmath>
#include <map>

#include "CliCommand.h"
#include "core/image/ImageMetrics.h"
#include "core/io/Catalog.h"
#include "core/scene/DefaultPreset.h"
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
    constexpr int kW = 900, kH = 600, kLeft = 70, kRight = 20, kTop = 40, kBottom = 60;
    QImage image(kW, kH, QImage::Format_RGB32);
    image.fill(Qt::white);
    QPainter p(&image);
    p.setRenderHint(QPainter::Antialiasing);
    double lo = 1e300, hi = 0.0, dbLo = 1e300, dbHi = 0.0;
    for (const LodPoint& q : points) {
        lo = std::min(lo, q.budgetMib);
        hi = std::max(hi, q.budgetMib);
        if (std::isfinite(q.psnrDb)) {
            dbLo = std::min(dbLo, q.psnrDb);
            dbHi = std::max(dbHi, q.psnrDb);
        }
    }
    const double xLo = std::floor(std::log2(lo)), xHi = std::max(std::ceil(std::log2(hi)), xLo + 1);
    const double yMin = std::floor(dbLo / 5.0) * 5.0, yMax = std::ceil(dbHi / 5.0) * 5.0 + 5.0;
    const auto px = [&](double mib) {
        return kLeft + (std::log2(mib) - xLo) / (xHi - xLo) * (kW - kLeft - kRight);
    };
    const auto py = [&](double db) {
        const double v = std::clamp(std::isfinite(db) ? db : yMax, yMin, yMax);
        return kTop + (yMax - v) / (yMax - yMin) * (kH - kTop - kBottom);
    };
    p.setPen(QColor(120, 120, 120));
    for (double d = yMin; d <= yMax; d += 5) {
        p.drawLine(QPointF(kLeft - 4, py(d)), QPointF(kLeft, py(d)));
        p.drawText(QRectF(0, py(d) - 8, kLeft - 8, 16), Qt::AlignRight | Qt::AlignVCenter,
                   QString::number(d));
    }
    for (double e = xLo; e <= xHi; e += 1) {
        const double mib = std::exp2(e);
        p.drawLine(QPointF(px(mib), kH - kBottom), QPointF(px(mib), kH - kBottom + 4));
        p.drawText(QRectF(px(mib) - 40, kH - kBottom + 6, 80, 16), Qt::AlignCenter,
                   QString::number(mib) + " MiB");
    }
    p.drawRect(QRectF(QPointF(kLeft, kTop), QPointF(kW - kRight, kH - kBottom)));
    p.setPen(Qt::black);
    p.drawText(QRectF(0, 8, kW, 20), Qt::AlignCenter, title);
    p.drawText(
        QRectF(0, kH - 28, kW, 20), Qt::AlignCenter,
        "GPU budget (log 2)   |   red: per-brick levels   |   blue: one level for the volume");
    p.save();
    p.translate(16, kH / 2.0);
    p.rotate(-90);
    p.drawText(QRectF(-120, -10, 240, 20), Qt::AlignCenter, "PSNR (dB) vs no budget");
    p.restore();
    for (const auto& [policy, colour] : {std::pair{std::string("per-brick"), QColor(200, 30, 30)},
                                         std::pair{std::string("uniform"), QColor(40, 80, 200)}}) {
        QPainterPath line;
        bool first = true;
        for (const LodPoint& q : points) {
            if (q.policy != policy) {
                continue;
            }
            const QPointF at(px(q.budgetMib), py(q.psnrDb));
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
    p.end();
    if (!image.save(path, "PNG")) {
        throw std::runtime_error("cannot write the plot " + path.toStdString());
    }
}

} // namespace

int runLodBench(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription("bench lod PATH: PSNR against the frame without a budget, "
                                     "for each GPU budget, per-brick levels and one level.");
    parser.addPositionalArgument("lod", "The bench to run (lod).");
    parser.addPositionalArgument("PATH", "DICOM folder, file or DICOMDIR, or a volume file");
    parser.addOptions({
        {"series", "Series id or UID (default: the largest volume).", "UID"},
        {"size", "Image size (default 256x256).", "WxH", "256x256"},
        {"preset", "Transfer function preset (default ct-bone, or mr-default).", "NAME"},
        {"budgets", "Budgets in MiB (default 1,2,4,8,16,32,64).", "LIST", "1,2,4,8,16,32,64"},
        {"csv", "Write every point as CSV.", "OUT.csv"},
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
        const std::string preset = parser.isSet("preset")
                                       ? parser.value("preset").toStdString()
                                       : defaultPresetName(volume.modality, d.mode);
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
        if (parser.isSet("csv")) {
            QFile f(parser.value("csv"));
            if (!f.open(QIODevice::WriteOnly | QIODevice::Truncate)) {
                err << "lucent-cli bench: cannot write " << parser.value("csv") << "\n";
                return kBadInput;
            }
            QTextStream(&f) << header << rows;
        }
        if (parser.isSet("plot") && !points.empty()) {
            writeLodPlot(
                points, parser.value("plot"),
                QStringLiteral("%1, %2, %3x%4, gl")
                    .arg(QString::fromStdString(volume.description.empty() ? pos[1].toStdString()
                                                                           : volume.description))
                    .arg(QString::fromStdString(preset))
                    .arg(width)
                    .arg(height));
        }
        out << header << rows;
    } catch (const std::exception& e) {
        err << "lucent-cli bench: " << e.what() << "\n";
        return kBadInput;
    }
    return kOk;
}

} // namespace lucent::cli
