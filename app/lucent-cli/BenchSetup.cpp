#include "BenchSetup.h"

#include <QFile>
#include <QTextStream>

#include <stdexcept>

#include "core/scene/DefaultPreset.h"

namespace lucent::cli {

void addVolumeBenchOptions(QCommandLineParser& parser) {
    parser.addOptions({
        {"series", "Series id or UID (default: the largest volume).", "UID"},
        {"size", "Image size (default 256x256).", "WxH", "256x256"},
        {"preset", "Transfer function preset (default ct-bone, or mr-default).", "NAME"},
        {"csv", "Write every point as CSV.", "OUT.csv"},
    });
}

std::string benchPreset(const QCommandLineParser& parser, const Volume& volume, RenderMode mode) {
    return parser.isSet("preset") ? parser.value("preset").toStdString()
                                  : defaultPresetName(volume.modality, mode);
}

QString benchPlotTitle(const QString& path, const Volume& volume, const std::string& preset,
                       int width, int height, const QString& renderer) {
    return QStringLiteral("%1, %2, %3x%4, %5")
        .arg(volume.description.empty() ? path : QString::fromStdString(volume.description))
        .arg(QString::fromStdString(preset))
        .arg(width)
        .arg(height)
        .arg(renderer);
}

void writeBenchCsv(const QCommandLineParser& parser, const QString& text) {
    if (!parser.isSet("csv")) {
        return;
    }
    QFile f(parser.value("csv"));
    if (!f.open(QIODevice::WriteOnly | QIODevice::Truncate)) {
        throw std::runtime_error("cannot write " + parser.value("csv").toStdString());
    }
    QTextStream(&f) << text;
}

} // namespace lucent::cli
