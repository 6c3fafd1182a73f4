// lucent-cli info PATH [--json]
#include <QCommandLineParser>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTextStream>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <vector>

#include "CliCommand.h"
#include "TerminalProgress.h"
#include "core/io/Catalog.h"
#include "core/dicom/PetSuvReader.h"
#include "core/stack/ImageStack.h"

namespace lucent::cli {
namespace {

QJsonArray vec(const glm::dvec3& v) {
    return {v.x, v.y, v.z};
}

// "2D stack, 6 frames, RGB"
std::string stackLabel(const SeriesEntry& e) {
    return describeStack(static_cast<int>(e.slices.size()), e.pixels.photometric,
                         e.pixels.samplesPerPixel);
}

// A PET series' SUVbw factor, or why it has none (core/pet).
struct SuvFactor {
    std::optional<double> factor;
    std::string refusal;
};

std::optional<SuvFactor> suvFactor(const SeriesEntry& e) {
    if (e.format != SourceFormat::Dicom || e.modality != "PT") {
        return std::nullopt;
    }
    std::vector<std::filesystem::path> files;
    for (const SliceRef& s : e.slices) {
        if (std::find(files.begin(), files.end(), s.file) == files.end()) {
            files.emplace_back(s.file);
        }
    }
    try {
        return SuvFactor{suvBwFactor(readSuvParameters(files)), {}};
    } catch (const std::exception& error) {
        return SuvFactor{std::nullopt, error.what()};
    }
}

QJsonObject toJson(const SeriesEntry& e) {
    const VolumeGeometry& g = e.geometry;
    QJsonArray warnings;
    for (const std::string& w : e.warnings) {
        warnings.append(QString::fromStdString(w));
    }
    QJsonObject o{
        {"uid", QString::fromStdString(e.seriesUid)},
        {"id", QString::fromStdString(e.id)},
        {"modality", QString::fromStdString(e.modality)},
        {"description", QString::fromStdString(e.description)},
        {"kind", seriesKindName(e.kind)},
        {"dims", QJsonArray{g.dims.x, g.dims.y, g.dims.z}},
        {"spacing", vec(g.spacing)},
        {"origin", vec(g.origin)},
        {"direction", QJsonArray{vec(g.direction[0]), vec(g.direction[1]), vec(g.direction[2])}},
        {"voxel_type", voxelTypeName(e.voxelType)},
        {"images", static_cast<int>(e.format == SourceFormat::Dicom ? e.slices.size() : 1)},
        {"resampled", e.resampled},
        {"warnings", warnings},
    };
    if (e.format == SourceFormat::Dicom) {
        o["photometric"] = QString::fromStdString(e.pixels.photometric);
        o["samples_per_pixel"] = e.pixels.samplesPerPixel;
    }
    if (e.kind == SeriesKind::Stack) {
        o["stack"] = QString::fromStdString(stackLabel(e));
    }
    if (const auto suv = suvFactor(e)) {
        if (suv->factor) {
            o["suv_bw_factor"] = *suv->factor;
        } else {
            o["suv_bw_refused"] = QString::fromStdString(suv->refusal);
        }
    }
    return o;
}

QString fixed(double v, int decimals) {
    return QString::number(v, 'f', decimals);
}

void printTable(const Catalog& catalog, QTextStream& out) {
    out << QString("%1  %2  %3  %4  %5  %6\n")
               .arg("#", -3)
               .arg("kind", -9)
               .arg("mod", -4)
               .arg("dims", -15)
               .arg("spacing (mm)", -24)
               .arg("description");
    int n = 1;
    for (const SeriesEntry& e : catalog.series) {
        const VolumeGeometry& g = e.geometry;
        out << QString("%1  %2  %3  %4  %5  %6\n")
                   .arg(n++, -3)
                   .arg(seriesKindName(e.kind), -9)
                   .arg(QString::fromStdString(e.modality), -4)
                   .arg(QString("%1x%2x%3").arg(g.dims.x).arg(g.dims.y).arg(g.dims.z), -15)
                   .arg(QString("%1 x %2 x %3")
                            .arg(fixed(g.spacing.x, 4), fixed(g.spacing.y, 4),
                                 fixed(g.spacing.z, 4)),
                        -24)
                   .arg(QString::fromStdString(e.description));
        out << "     id: " << QString::fromStdString(e.id) << "\n";
        if (e.kind == SeriesKind::Stack) {
            out << "     " << QString::fromStdString(stackLabel(e)) << "\n";
        }
        if (const auto suv = suvFactor(e)) {
            out << "     SUVbw: "
                << (suv->factor ? QString("factor %1 (g/mL per Bq/mL)").arg(*suv->factor, 0, 'g', 6)
                                : "not computed: " + QString::fromStdString(suv->refusal))
                << "\n";
        }
        out << "     origin (LPS mm): " << fixed(g.origin.x, 2) << ", " << fixed(g.origin.y, 2)
            << ", " << fixed(g.origin.z, 2) << "\n";
        for (const std::string& w : e.warnings) {
            out << "     warning: " << QString::fromStdString(w) << "\n";
        }
    }
    if (!catalog.skipped.empty()) {
        out << catalog.skipped.size() << " file(s) skipped:\n";
        for (const SkippedFile& s : catalog.skipped) {
            out << "  " << QString::fromStdString(s.file) << ": "
                << QString::fromStdString(s.reason) << "\n";
        }
    }
}

} // namespace

int runInfo(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription("Lists the series a path holds, with their geometry.");
    parser.addPositionalArgument("PATH", "DICOM folder, file or DICOMDIR, or a volume file");
    parser.addOption({"json", "Print JSON instead of a table."});
    parser.addHelpOption();
    QTextStream err(stderr);
    if (!parser.parse(args)) {
        err << "lucent-cli info: " << parser.errorText() << "\n";
        return kUsage;
    }
    if (parser.isSet("help")) {
        QTextStream(stdout) << parser.helpText();
        return kOk;
    }
    if (parser.positionalArguments().size() != 1) {
        err << "lucent-cli info: expected exactly one PATH\n" << parser.helpText();
        return kUsage;
    }
    const QString path = parser.positionalArguments().front();
    Catalog catalog;
    const TerminalProgress progress;
    try {
        catalog = scanPath(path.toStdString(), progress.control());
        progress.finish();
    } catch (const std::exception& e) {
        progress.finish();
        err << "lucent-cli info: " << e.what() << "\n";
        return kBadInput;
    }
    QTextStream out(stdout);
    if (parser.isSet("json")) {
        QJsonArray series;
        for (const SeriesEntry& e : catalog.series) {
            series.append(toJson(e));
        }
        QJsonArray skipped;
        for (const SkippedFile& s : catalog.skipped) {
            skipped.append(QJsonObject{{"file", QString::fromStdString(s.file)},
                                       {"reason", QString::fromStdString(s.reason)}});
        }
        out << QJsonDocument(QJsonObject{{"series", series}, {"skipped", skipped}})
                   .toJson(QJsonDocument::Indented);
    } else {
        printTable(catalog, out);
    }
    if (catalog.series.empty()) {
        err << "lucent-cli info: " << path << ": nothing loadable";
        if (!catalog.skipped.empty()) {
            err << " (" << QString::fromStdString(catalog.skipped.front().file) << ": "
                << QString::fromStdString(catalog.skipped.front().reason) << ")";
        }
        err << "\n";
        return kBadInput;
    }
    return kOk;
}

} // namespace lucent::cli
