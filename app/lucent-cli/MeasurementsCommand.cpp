// lucent-cli measurements: the measurements of a series in the study store, or
// of one SR file (core/report), as text or JSON; with --patient ID --recist, the
// patient's RECIST 1.1 follow-up table (core/followup).
#include <QCommandLineParser>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTextStream>

#include "CliCommand.h"
#include "core/exchange/InstanceFiles.h"
#include "core/followup/FollowUpCollection.h"
#include "core/followup/FollowUpText.h"
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

QString storeFolder(const QCommandLineParser& p) {
    return p.isSet("store") ? p.value("store") : PacsConfig::defaultStoreFolder();
}

QJsonValue optionalNumber(const std::optional<double>& v) {
    return v ? QJsonValue(*v) : QJsonValue(QJsonValue::Null);
}

QJsonArray strings(const std::vector<std::string>& list) {
    QJsonArray out;
    for (const std::string& s : list) {
        out.append(QString::fromStdString(s));
    }
    return out;
}

QJsonObject toJson(const LesionRow& row) {
    QJsonArray at;
    for (const std::optional<LesionObservation>& o : row.at) {
        if (!o) {
            at.append(QJsonValue::Null);
            continue;
        }
        const glm::dvec3& c = o->where.centre;
        at.append(QJsonObject{{"diameter_mm", o->diameterMm},
                              {"long_axis_mm", o->longAxisMm},
                              {"short_axis_mm", o->shortAxisMm},
                              {"gone", o->gone},
                              {"text", QString::fromStdString(formatLesionCell(row, o))},
                              {"series_uid", QString::fromStdString(o->where.seriesUid)},
                              {"centre_lps_mm", QJsonArray{c.x, c.y, c.z}}});
    }
    return {{"tracking_uid", QString::fromStdString(row.trackingUid)},
            {"name", QString::fromStdString(row.name)},
            {"role", lesionRoleName(row.role)},
            {"lymph_node", row.lymphNode},
            {"new_lesion", row.firstTimepoint > 0},
            {"timepoints", at}};
}

void printFollowUp(const FollowUpSources& sources, bool json, QTextStream& out) {
    const FollowUpTable table = assessRecist(sources.timepoints);
    if (json) {
        QJsonArray timepoints, lesions;
        for (const TimepointAssessment& t : table.timepoints) {
            timepoints.append(
                QJsonObject{{"study_date", QString::fromStdString(formatStudyDate(t.studyDate))},
                            {"study_uids", strings(t.studyUids)},
                            {"sum_mm", t.sumMm},
                            {"evaluable", t.evaluable},
                            {"nadir_mm", optionalNumber(t.nadirMm)},
                            {"change_from_baseline_percent", optionalNumber(t.fromBaselinePercent)},
                            {"change_from_nadir_percent", optionalNumber(t.fromNadirPercent)},
                            {"response", recistResponseName(t.response)},
                            {"reasons", strings(t.reasons)}});
        }
        for (const LesionRow& row : table.lesions) {
            lesions.append(toJson(row));
        }
        out << QJsonDocument(
                   QJsonObject{{"patient_id", QString::fromStdString(sources.patientId)},
                               {"patient_name", QString::fromStdString(sources.patientName)},
                               {"timepoints", timepoints},
                               {"lesions", lesions},
                               {"problems", strings(sources.problems)}})
                   .toJson();
        return;
    }
    out << "Patient " << QString::fromStdString(sources.patientId) << " ("
        << QString::fromStdString(sources.patientName) << "), RECIST 1.1, "
        << table.timepoints.size() << " timepoint(s), " << table.lesions.size()
        << " tracked lesion(s)\n"
        << QString::fromStdString(followUpText(table));
    for (const std::string& p : sources.problems) {
        out << "not read: " << QString::fromStdString(p) << "\n";
    }
}

} // namespace

int runMeasurements(const QStringList& args) {
    QCommandLineParser p;
    p.setApplicationDescription(
        "Prints the measurements of a series in the study store (from every DICOM SR there "
        "that refers to it), or of one SR file, and what of them cannot be shown; or a "
        "patient's RECIST 1.1 follow-up table (--patient ID --recist).");
    p.addOptions({
        {"series", "A Series Instance UID of the study store.", "UID"},
        {"patient", "With --recist: a Patient ID of the study store.", "ID"},
        {"recist", "The patient's RECIST 1.1 follow-up table: tracked lesions by timepoint, sum of "
                   "diameters, change from baseline and nadir, response."},
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
    const int sources = static_cast<int>(p.positionalArguments().size()) +
                        (p.isSet("series") ? 1 : 0) + (p.isSet("patient") ? 1 : 0);
    if (sources != 1 || p.isSet("recist") != p.isSet("patient")) {
        err << "lucent-cli measurements: give one SR FILE, --series UID, or --patient ID "
               "--recist\n";
        return kUsage;
    }
    QTextStream out(stdout);
    try {
        if (p.isSet("patient")) {
            StudyStore store(storeFolder(p).toStdString());
            printFollowUp(collectFollowUp(store, p.value("patient").toStdString()), p.isSet("json"),
                          out);
            return kOk;
        }
        if (p.isSet("series")) {
            StudyStore store(storeFolder(p).toStdString());
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
