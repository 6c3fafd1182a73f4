// lucent-cli measurements: the measurements of a series in the study store, or
// of one SR file (core/report), as text or JSON.
#include <QCommandLineParser>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTextStream>

#include "CliCommand.h"
#include "core/exchange/InstanceFiles.h"
#include "core/pacs/PacsConfig.h"
#include "core/report/MeasurementArchive.h"
#include "core/report/MeasurementReport.h"

namespace lucent::cli {
namespace {

QJsonObject toJson(const Measurement& m) {
    QJsonArray points;
    for (const glm::dvec3& p : m.points) {
        points.append(QJsonArray{p.x, p.y, p.z});
    }
    return {{"id", static_cast<double>(m.id)},
            {"kind", measurementKindName(m.kind)},
            {"label", QString::fromStdString(m.label)},
            {"value", QString::fromStdString(measurementValueText(m))},
            {"points_lps_mm", points},
            {"read_only", m.readOnly}};
}

void print(const std::vector<Measurement>& measurements, const std::vector<std::string>& notShown,
           bool json, QTextStream& out) {
    if (json) {
        QJsonArray list, missing;
        for (const Measurement& m : measurements) {
            list.append(toJson(m));
        }
        for (const std::string& s : notShown) {
            missing.append(QString::fromStdString(s));
        }
        out << QJsonDocument(QJsonObject{{"measurements", list}, {"not_shown", missing}}).toJson();
        return;
    }
    for (const Measurement& m : measurements) {
        out << "#" << m.id << "  " << measurementKindName(m.kind) << "  "
            << (m.label.empty() ? QString("-") : QString::fromStdString(m.label)) << "  "
            << QString::fromStdString(measurementValueText(m))
            << (m.readOnly ? "  (read-only)" : "") << "\n";
    }
    out << measurements.size() << " measurement(s)\n";
    for (const std::string& s : notShown) {
        out << "not shown: " << QString::fromStdString(s) << "\n";
    }
}

} // namespace

int runMeasurements(const QStringList& args) {
    QCommandLineParser p;
    p.setApplicationDescription(
        "Prints the measurements of a series in the study store (from every DICOM SR there "
        "that refers to it), or of one SR file, and what of them cannot be shown.");
    p.addOptions({
        {"series", "A Series Instance UID of the study store.", "UID"},
        {"store", "The study store folder (default: ~/.local/share/lucent/store).", "DIR"},
        {"images",
         "With an SR FILE: the folder of the images it refers to, to place 2D coordinates of SRs "
         "Lucent did not write.",
         "DIR"},
        {"json", "JSON instead of text."},
    });
    p.addPositionalArgument("FILE", "An SR file (instead of --series).", "[FILE]");
    p.addHelpOption();
    QTextStream err(stderr);
    if (!p.parse(args)) {
        err << "lucent-cli measurements: " << p.errorText() << "\n";
        return kUsage;
    }
    if (p.isSet("help")) {
        QTextStream(stdout) << p.helpText();
        return kOk;
    }
    if (p.positionalArguments().size() + (p.isSet("series") ? 1 : 0) != 1) {
        err << "lucent-cli measurements: give one SR FILE or --series UID\n";
        return kUsage;
    }
    QTextStream out(stdout);
    try {
        if (p.isSet("series")) {
            const QString folder =
                p.isSet("store") ? p.value("store") : PacsConfig::defaultStoreFolder();
            StudyStore store(folder.toStdString());
            MeasurementArchive archive(store);
            const MeasurementArchive::Loaded loaded = archive.load(p.value("series").toStdString());
            print(loaded.measurements, loaded.notShown, p.isSet("json"), out);
            return kOk;
        }
        ReferencedSeries images;
        if (p.isSet("images")) {
            std::vector<std::string> passedOver;
            std::vector<std::filesystem::path> files;
            for (const InstanceHeader& h :
                 collectInstances(p.value("images").toStdString(), "", passedOver)) {
                files.push_back(h.file);
            }
            images = readReferencedSeries(files);
        }
        const ReadReport report = readMeasurementReport(p.positionalArguments()[0].toStdString(),
                                                        p.isSet("images") ? &images : nullptr);
        print(report.measurements, report.notShown, p.isSet("json"), out);
        return kOk;
    } catch (const std::exception& e) {
        err << "lucent-cli measurements: " << e.what() << "\n";
        return kBadInput;
    }
}

} // namespace lucent::cli
