// lucent-cli hang PATH... [--protocol NAME] [--protocols DIR] [--current UID] [--set N]
//                         [--priors-pending] [--json]
// Which hanging protocol wins for the series under the paths, and which series goes where.
#include <QCommandLineParser>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QStandardPaths>
#include <QTextStream>

#include <algorithm>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "CliCommand.h"
#include "core/hanging/HangingProtocolJson.h"
#include "core/io/Catalog.h"

namespace lucent::cli {
namespace {

QString q(const std::string& s) {
    return QString::fromStdString(s);
}

QString studyOrderName(int order) {
    return order == 0 ? QString("current") : order > 0 ? QString("prior %1").arg(order) : "other";
}

QJsonObject seriesJson(const HangingSeries& s) {
    return QJsonObject{
        {"uid", q(s.seriesUid)},
        {"id", q(s.id)},
        {"path", q(s.path)},
        {"study_uid", q(s.studyUid)},
        {"study_date", q(s.studyDate)},
        {"study_time", q(s.studyTime)},
        {"study_order", s.studyOrder},
        {"patient_id", q(s.patientId)},
        {"modality", q(s.modality)},
        {"body_part", q(s.bodyPart)},
        {"description", q(s.description)},
        {"series_number", s.seriesNumber},
        {"slice_thickness", s.sliceThickness},
        {"orientation", sliceOrientationName(s.orientation)},
        {"instances", s.instances},
        {"kind", seriesKindName(s.kind)},
    };
}

QJsonObject resultJson(const HangingResult& r) {
    const HangingProtocol& p = *r.protocol;
    const ViewportSet* set = p.viewportSets.empty() ? nullptr : &p.viewportSets[r.viewportSet];
    QJsonArray viewports;
    for (const ViewportAssignment& v : r.viewports) {
        viewports.append(QJsonObject{
            {"row", v.spec.row},
            {"column", v.spec.column},
            {"row_span", v.spec.rowSpan},
            {"column_span", v.spec.columnSpan},
            {"slot", q(v.spec.seriesSlot)},
            {"view", viewportViewName(v.spec.view)},
            {"window", q(v.spec.windowPreset)},
            {"link", v.spec.linkGroup},
            {"series", v.series ? QJsonValue(seriesJson(*v.series)) : QJsonValue()},
        });
    }
    QJsonArray missing;
    for (int order : r.missingStudyOrders) {
        missing.append(order);
    }
    return QJsonObject{
        {"protocol", q(p.name)},
        {"file", q(p.file)},
        {"score", r.score},
        {"applicable", r.applicable},
        {"reason", q(r.reason)},
        {"viewport_set", r.viewportSet},
        {"viewport_set_name", set ? q(set->name) : QString()},
        {"rows", set ? set->rows : 0},
        {"columns", set ? set->columns : 0},
        {"viewports", viewports},
        {"missing_study_orders", missing},
    };
}

void printSeries(const std::vector<HangingSeries>& series, QTextStream& out) {
    out << "series:\n";
    for (const HangingSeries& s : series) {
        out << QString("  %1  %2 %3  %4 %5  %6  %7 mm  %8 images  \"%9\"\n")
                   .arg(studyOrderName(s.studyOrder), -8)
                   .arg(q(s.studyDate), q(s.studyTime.substr(0, 6)))
                   .arg(q(s.modality), -3)
                   .arg(seriesKindName(s.kind), -9)
                   .arg(sliceOrientationName(s.orientation), -8)
                   .arg(s.sliceThickness)
                   .arg(s.instances)
                   .arg(q(s.description));
        out << "      " << q(s.id) << "\n";
    }
}

void printResult(const HangingResult& r, QTextStream& out) {
    const HangingProtocol& p = *r.protocol;
    out << "protocol: " << q(p.name) << "  score " << r.score << "  (" << q(p.file) << ")\n";
    if (!r.applicable) {
        out << "  not applicable: " << q(r.reason) << "\n";
    }
    if (!p.viewportSets.empty()) {
        const ViewportSet& set = p.viewportSets[r.viewportSet];
        out << "viewport set " << r.viewportSet << " \"" << q(set.name) << "\" (" << set.rows << "x"
            << set.columns << "):\n";
    }
    for (const ViewportAssignment& v : r.viewports) {
        out << QString("  [%1,%2] %3  %4  %5")
                   .arg(v.spec.row)
                   .arg(v.spec.column)
                   .arg(q(v.spec.seriesSlot), -10)
                   .arg(viewportViewName(v.spec.view), -8)
                   .arg(v.spec.windowPreset.empty() ? QString("-") : q(v.spec.windowPreset), -11);
        if (v.series) {
            out << QString("%1  %2 (%3)  \"%4\"\n")
                       .arg(q(v.series->seriesUid), q(v.series->studyDate),
                            studyOrderName(v.series->studyOrder), q(v.series->description));
        } else {
            out << "(empty)\n";
        }
    }
    for (int order : r.missingStudyOrders) {
        out << "missing: prior " << order << " (asked for, not among the series)\n";
    }
}

void printRanking(const std::vector<HangingResult>& ranking, QTextStream& out) {
    out << "ranking:\n";
    int n = 1;
    for (const HangingResult& r : ranking) {
        out << QString("  %1. %2  score %3  %4/%5 viewports")
                   .arg(n++)
                   .arg(q(r.protocol->name), -36)
                   .arg(r.score, 0, 'g', 4)
                   .arg(r.filledViewports())
                   .arg(r.viewports.size());
        out << (r.applicable ? "" : "  not applicable: " + q(r.reason)) << "\n";
    }
}

const HangingProtocol* findProtocol(const std::vector<HangingProtocol>& protocols,
                                    const std::string& name) {
    for (const HangingProtocol& p : protocols) {
        if (p.name == name || std::filesystem::path(p.file).stem() == name) {
            return &p;
        }
    }
    return nullptr;
}

// The series with their study order (current, priors 1, 2, ..., others last),
// then by series number.
std::vector<HangingSeries> studiesInOrder(std::vector<HangingSeries> series,
                                          const std::string& current) {
    series = orderStudies(std::move(series), current);
    std::stable_sort(series.begin(), series.end(),
                     [](const HangingSeries& a, const HangingSeries& b) {
                         const auto rank = [](int order) { return order < 0 ? 1 << 30 : order; };
                         return std::make_tuple(rank(a.studyOrder), a.seriesNumber) <
                                std::make_tuple(rank(b.studyOrder), b.seriesNumber);
                     });
    return series;
}

// --json: the ranking, the series, the protocol files' errors and the result (null: none).
void printJson(const std::vector<HangingResult>& ranking, const std::vector<HangingSeries>& series,
               const std::vector<std::string>& errors, const std::optional<HangingResult>& result,
               QTextStream& out) {
    QJsonArray rankingJson, seriesList, errorList;
    for (const HangingResult& r : ranking) {
        rankingJson.append(QJsonObject{{"protocol", q(r.protocol->name)},
                                       {"file", q(r.protocol->file)},
                                       {"score", r.score},
                                       {"applicable", r.applicable},
                                       {"reason", q(r.reason)},
                                       {"filled_viewports", r.filledViewports()}});
    }
    for (const HangingSeries& s : series) {
        seriesList.append(seriesJson(s));
    }
    for (const std::string& e : errors) {
        errorList.append(q(e));
    }
    QJsonObject root{{"ranking", rankingJson}, {"series", seriesList}, {"errors", errorList}};
    root["result"] = result ? QJsonValue(resultJson(*result)) : QJsonValue();
    out << QJsonDocument(root).toJson(QJsonDocument::Indented);
}

} // namespace

int runHang(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(
        "Which hanging protocol wins for the series under PATH..., and which series goes into "
        "which viewport. The current study is the newest (by study date and time) unless "
        "--current names one; the same patient's older studies are priors 1, 2, ...");
    parser.addPositionalArgument("PATH", "DICOM folders, files or DICOMDIRs", "PATH...");
    parser.addOption({"protocol", "Apply this protocol (its name or file stem).", "NAME"});
    parser.addOption({"protocols",
                      "The user's protocol folder (default: <data home>/lucent/hanging); read "
                      "before the shipped ones.",
                      "DIR"});
    parser.addOption({"current", "The current study (Study Instance UID).", "UID"});
    parser.addOption({"set", "The viewport set to show (default 0).", "N"});
    parser.addOption({"priors-pending",
                      "Rank as before the priors lookup: a required prior that is not there "
                      "does not make a protocol inapplicable."});
    parser.addOption({"json", "Print JSON."});
    parser.addHelpOption();
    QTextStream err(stderr);
    if (!parser.parse(args)) {
        err << "lucent-cli hang: " << parser.errorText() << "\n";
        return kUsage;
    }
    if (parser.isSet("help")) {
        QTextStream(stdout) << parser.helpText();
        return kOk;
    }
    if (parser.positionalArguments().isEmpty()) {
        err << "lucent-cli hang: expected at least one PATH\n" << parser.helpText();
        return kUsage;
    }
    const std::filesystem::path userFolder =
        parser.isSet("protocols") ? std::filesystem::path(parser.value("protocols").toStdString())
                                  : userHangingFolder(QStandardPaths::writableLocation(
                                                          QStandardPaths::GenericDataLocation)
                                                          .toStdString());
    std::vector<std::string> errors;
    const std::vector<HangingProtocol> protocols =
        loadHangingProtocols(hangingFolders(userFolder), &errors);
    for (const std::string& e : errors) {
        err << "lucent-cli hang: " << q(e) << "\n";
    }
    std::vector<HangingSeries> series;
    try {
        for (const QString& path : parser.positionalArguments()) {
            const Catalog catalog = scanPath(path.toStdString());
            for (const SeriesEntry& e : catalog.series) {
                series.push_back(hangingSeriesOf(e, path.toStdString()));
            }
        }
    } catch (const std::exception& e) {
        err << "lucent-cli hang: " << e.what() << "\n";
        return kBadInput;
    }
    if (series.empty()) {
        err << "lucent-cli hang: nothing loadable under the paths\n";
        return kBadInput;
    }
    series = studiesInOrder(std::move(series), parser.value("current").toStdString());
    const RankOptions options{!parser.isSet("priors-pending")};
    const int set = parser.isSet("set") ? static_cast<int>(numberFlag(parser, "set", 0)) : 0;
    try {
        const std::vector<HangingResult> ranking = rankProtocols(protocols, series, options);
        const HangingProtocol* chosen = nullptr;
        if (parser.isSet("protocol")) {
            chosen = findProtocol(protocols, parser.value("protocol").toStdString());
            if (chosen == nullptr) {
                QStringList names;
                for (const HangingProtocol& p : protocols) {
                    names << q(p.name);
                }
                err << "lucent-cli hang: --protocol: no protocol '" << parser.value("protocol")
                    << "'; the protocols are: " << names.join(", ") << "\n";
                return kUsage;
            }
        } else if (!ranking.empty() && ranking.front().applicable) {
            chosen = ranking.front().protocol;
        }
        QTextStream out(stdout);
        const std::optional<HangingResult> result =
            chosen ? std::optional(applyProtocol(*chosen, series, set, options)) : std::nullopt;
        if (parser.isSet("json")) {
            printJson(ranking, series, errors, result, out);
        } else {
            printSeries(series, out);
            printRanking(ranking, out);
            if (result) {
                printResult(*result, out);
            } else {
                out << "protocol: none applies\n";
            }
        }
        if (!result) {
            err << "lucent-cli hang: no protocol applies to these series\n";
        }
    } catch (const std::exception& e) {
        err << "lucent-cli hang: " << e.what() << "\n";
        return kBadInput;
    }
    return errors.empty() ? kOk : kBadInput;
}

} // namespace lucent::cli
