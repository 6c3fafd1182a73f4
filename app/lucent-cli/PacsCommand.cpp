// lucent-cli pacs echo|find|get ...: DICOM networking from the command line.
#include <QCommandLineParser>
#include <QElapsedTimer>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTextStream>

#include "CliCommand.h"
#include "PacsOptions.h"
#include <QDir>
#include <QStandardPaths>

#include <memory>

#include "core/pacs/DicomWebClient.h"
#include "core/pacs/DimseQuery.h"
#include "core/pacs/SeriesRetriever.h"
#include "core/pacs/StorageScp.h"

namespace lucent::cli {
namespace {

QJsonObject toJson(const QueryMatch& m) {
    QJsonObject o{{"level", QString(queryLevelName(m.level)).toLower()},
                  {"patient_name", QString::fromStdString(m.patientName)},
                  {"patient_id", QString::fromStdString(m.patientId)}};
    if (m.level == QueryLevel::Patient) {
        o["birth_date"] = QString::fromStdString(m.patientBirthDate);
        return o;
    }
    o["study_uid"] = QString::fromStdString(m.studyUid);
    o["study_date"] = QString::fromStdString(m.studyDate);
    o["study_description"] = QString::fromStdString(m.studyDescription);
    o["accession"] = QString::fromStdString(m.accessionNumber);
    o["instances"] = m.instances;
    if (m.level == QueryLevel::Study) {
        o["modalities"] = QString::fromStdString(m.modalitiesInStudy);
    } else {
        o["series_uid"] = QString::fromStdString(m.seriesUid);
        o["series_number"] = m.seriesNumber;
        o["series_description"] = QString::fromStdString(m.seriesDescription);
        o["modality"] = QString::fromStdString(m.modality);
    }
    return o;
}

void printTable(const std::vector<QueryMatch>& matches, QTextStream& out) {
    for (const QueryMatch& m : matches) {
        QStringList cols{QString::fromStdString(m.patientName),
                         QString::fromStdString(m.patientId)};
        if (m.level != QueryLevel::Patient) {
            cols << QString::fromStdString(m.studyDate)
                 << QString::fromStdString(m.accessionNumber);
        }
        if (m.level == QueryLevel::Study) {
            cols << QString::fromStdString(m.modalitiesInStudy)
                 << QString::fromStdString(m.studyDescription)
                 << QString("%1 images").arg(m.instances) << QString::fromStdString(m.studyUid);
        } else if (m.level == QueryLevel::Series) {
            cols << QString::fromStdString(m.modality) << QString("#%1").arg(m.seriesNumber)
                 << QString::fromStdString(m.seriesDescription)
                 << QString("%1 images").arg(m.instances) << QString::fromStdString(m.seriesUid);
        }
        out << cols.join("  ") << "\n";
    }
    out << matches.size() << " match(es)\n";
}

int echoCommand(const QStringList& args) {
    QCommandLineParser p;
    p.setApplicationDescription("Checks that a PACS answers (C-ECHO).");
    addNodeOptions(p);
    QTextStream err(stderr);
    if (!p.parse(args)) {
        err << "lucent-cli pacs echo: " << p.errorText() << "\n";
        return kUsage;
    }
    if (p.isSet("help")) {
        QTextStream(stdout) << p.helpText();
        return kOk;
    }
    try {
        const auto [node, settings] = nodeFrom(p);
        QElapsedTimer timer;
        timer.start();
        echo(node, settings);
        QTextStream(stdout) << QString::fromStdString(node.describe()) << " answered C-ECHO in "
                            << timer.elapsed() << " ms\n";
    } catch (const std::invalid_argument& e) {
        err << "lucent-cli pacs echo: " << e.what() << "\n";
        return kUsage;
    } catch (const PacsError& e) {
        err << "lucent-cli pacs echo: " << e.what() << "\n";
        return kPacsFailure;
    }
    return kOk;
}

int findCommand(const QStringList& args) {
    QCommandLineParser p;
    p.setApplicationDescription("Searches a PACS (C-FIND).");
    addNodeOptions(p);
    p.addOptions({
        {"level", "patient, study (default) or series.", "LEVEL", "study"},
        {"patient-name", "Patient name, DICOM wildcards * and ? allowed.", "P"},
        {"patient-id", "Patient ID.", "ID"},
        {"modality", "Modality, or several separated by commas.", "M[,M]"},
        {"date", "Study date or range: YYYYMMDD, YYYYMMDD-YYYYMMDD, YYYYMMDD-, -YYYYMMDD.",
         "FROM-TO"},
        {"accession", "Accession number.", "A"},
        {"study", "Study Instance UID.", "UID"},
        {"wado", "Search this DICOMweb service (QIDO-RS) instead of --pacs.", "URL"},
        {"json", "Print a JSON list of matches."},
    });
    QTextStream err(stderr);
    if (!p.parse(args)) {
        err << "lucent-cli pacs find: " << p.errorText() << "\n";
        return kUsage;
    }
    if (p.isSet("help")) {
        QTextStream(stdout) << p.helpText();
        return kOk;
    }
    try {
        QueryLevel level = QueryLevel::Study;
        QueryFilter f;
        try {
            level = parseQueryLevel(p.value("level").toStdString());
            f.patientName = p.value("patient-name").toStdString();
            f.patientId = p.value("patient-id").toStdString();
            f.accessionNumber = p.value("accession").toStdString();
            f.studyUid = p.value("study").toStdString();
            f.dateRange = p.value("date").toStdString();
            for (const QString& m : p.value("modality").split(',', Qt::SkipEmptyParts)) {
                f.modalities.push_back(m.trimmed().toUpper().toStdString());
            }
            f.validate();
        } catch (const PacsError& e) {
            throw std::invalid_argument(e.what());
        }
        const std::vector<QueryMatch> matches =
            p.isSet("wado") ? qidoSearch(serviceFrom(p), level, f) : [&] {
                const auto [node, settings] = nodeFrom(p);
                return find(node, settings, level, f);
            }();
        QTextStream out(stdout);
        if (p.isSet("json")) {
            QJsonArray list;
            for (const QueryMatch& m : matches) {
                list.append(toJson(m));
            }
            out << QJsonDocument(list).toJson(QJsonDocument::Indented);
        } else {
            printTable(matches, out);
        }
    } catch (const std::invalid_argument& e) {
        err << "lucent-cli pacs find: " << e.what() << "\n";
        return kUsage;
    } catch (const PacsError& e) {
        err << "lucent-cli pacs find: " << e.what() << "\n";
        return kPacsFailure;
    }
    return kOk;
}

int getCommand(const QStringList& args) {
    QCommandLineParser p;
    p.setApplicationDescription("Retrieves a study or one series into the local study store.");
    addNodeOptions(p);
    p.addOptions({
        {"study", "Study Instance UID (required).", "UID"},
        {"series", "Series Instance UID (default: every series of the study).", "UID"},
        {"method",
         "cget (default), cmove (Lucent's storage SCP receives) or wado (with --wado URL).",
         "METHOD", "cget"},
        {"port",
         "Port of Lucent's storage SCP for --method cmove (default 11112); its AE title is --aet.",
         "N", "11112"},
        {"wado", "DICOMweb base URL for --method wado.", "URL"},
        {"store", "The study store folder.", "DIR"},
    });
    QTextStream err(stderr);
    if (!p.parse(args)) {
        err << "lucent-cli pacs get: " << p.errorText() << "\n";
        return kUsage;
    }
    if (p.isSet("help")) {
        QTextStream(stdout) << p.helpText();
        return kOk;
    }
    const QString store =
        p.isSet("store") ? p.value("store")
                         : QStandardPaths::writableLocation(QStandardPaths::GenericDataLocation) +
                               "/lucent/store";
    try {
        if (!p.isSet("study")) {
            throw std::invalid_argument("--study UID is required");
        }
        const QString method = p.value("method");
        if (method != "cget" && method != "wado" && method != "cmove") {
            throw std::invalid_argument("--method " + method.toStdString() +
                                        " is not one of cget, cmove, wado");
        }
        bool portOk = false;
        const int scpPort = p.value("port").toInt(&portOk);
        if (!portOk || scpPort < 1 || scpPort > 65535) {
            throw std::invalid_argument("--port must be a port number from 1 to 65535");
        }
        const bool wado = method == "wado";
        if (wado && !p.isSet("wado")) {
            throw std::invalid_argument("--method wado needs --wado URL");
        }
        const std::string study = p.value("study").toStdString();
        std::vector<std::string> series;
        if (p.isSet("series")) {
            series.push_back(p.value("series").toStdString());
        } else {
            QueryFilter f;
            f.studyUid = study;
            const std::vector<QueryMatch> found =
                wado ? qidoSearch(serviceFrom(p), QueryLevel::Series, f) : [&] {
                    const auto [node, settings] = nodeFrom(p);
                    return find(node, settings, QueryLevel::Series, f);
                }();
            for (const QueryMatch& m : found) {
                series.push_back(m.seriesUid);
            }
            if (series.empty()) {
                throw PacsError("no series found for study " + study);
            }
        }
        StudyStore target(QDir(store).absolutePath().toStdString());
        // C-MOVE: the PACS sends to Lucent's own storage SCP, on the same store.
        std::unique_ptr<StorageScp> scp;
        if (method == "cmove") {
            scp = std::make_unique<StorageScp>(
                target.root(), StorageScpSettings{p.value("aet").toStdString(), scpPort});
        }
        QTextStream out(stdout);
        bool allComplete = true;
        for (const std::string& uid : series) {
            const RetrieveResult r =
                wado ? wadoRetrieveSeries(serviceFrom(p), study, uid, target) : [&] {
                    const auto [node, settings] = nodeFrom(p);
                    return method == "cmove"
                               ? moveSeries(node, settings, p.value("aet").toStdString(), study,
                                            uid, target)
                               : retrieveSeries(node, settings, study, uid, target);
                }();
            allComplete = allComplete && r.complete;
            out << "series " << QString::fromStdString(uid) << ": " << r.received
                << " instance(s) arrived, " << r.alreadyStored << " already stored, "
                << (r.complete ? "complete" : "INCOMPLETE") << " ("
                << (r.alreadyStored + r.received) << "/" << r.expected << "), in "
                << QString::fromStdString(r.folder.string()) << "\n";
        }
        return allComplete ? kOk : kPacsFailure;
    } catch (const std::invalid_argument& e) {
        err << "lucent-cli pacs get: " << e.what() << "\n";
        return kUsage;
    } catch (const PacsError& e) {
        err << "lucent-cli pacs get: " << e.what() << "\n";
        return kPacsFailure;
    } catch (const StoreError& e) {
        err << "lucent-cli pacs get: " << e.what() << "\n";
        return kBadInput;
    }
}

} // namespace

int runPacs(const QStringList& args) {
    QTextStream err(stderr);
    if (args.size() < 2) {
        err << "usage: lucent-cli pacs echo|find|get|send ... (--help after the verb lists its "
               "options)\n";
        return kUsage;
    }
    QStringList rest = args;
    const QString verb = rest.takeAt(1);
    if (verb == "echo") {
        return echoCommand(rest);
    }
    if (verb == "find") {
        return findCommand(rest);
    }
    if (verb == "get") {
        return getCommand(rest);
    }
    if (verb == "send") {
        return runPacsSend(rest);
    }
    err << "lucent-cli pacs: unknown verb '" << verb << "' (echo, find, get, send)\n";
    return kUsage;
}

} // namespace lucent::cli
