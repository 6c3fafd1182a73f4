// lucent-cli register FIXED MOVING [--series UID] [--moving-series UID] [--affine]
//                     [--metric mi|ms] [--init auto|centres|frame] -o transform.json
//                     [--stats] [--sro reg.dcm]
// Rigid (then with --affine affine) registration of two series (core/registration): the
// 4x4 matrix that maps a point in the fixed series' LPS mm to the same anatomy in the
// moving series' LPS mm.
// --sro also writes it as a DICOM Spatial Registration object (core/exchange) in the
// fixed series' study and Frame of Reference.
#include <QCommandLineParser>
#include <QTextStream>

#include <optional>
#include <stdexcept>

#include "CliCommand.h"
#include "core/exchange/SpatialRegistrationSource.h"
#include "core/fusion/TransformFile.h"
#include "core/io/Catalog.h"
#include "core/registration/Registration.h"

namespace lucent::cli {
namespace {

const SeriesEntry& entryOf(const Catalog& catalog, const std::string& idOrUid,
                           const QString& path) {
    const SeriesEntry* e = idOrUid.empty() ? catalog.defaultEntry() : catalog.find(idOrUid);
    if (e == nullptr) {
        throw std::runtime_error(path.toStdString() + ": no such series");
    }
    return *e;
}

void addRegisterOptions(QCommandLineParser& parser) {
    parser.setApplicationDescription(
        "Rigid registration (versor rigid, ITK) of MOVING onto FIXED, then affine with "
        "--affine. Writes the 4x4 matrix that maps fixed LPS mm to moving LPS mm (row-major "
        "rows) with the metric, iterations and seconds.");
    parser.addPositionalArgument("FIXED", "the fixed series' path (DICOM folder, file, ...)");
    parser.addPositionalArgument("MOVING", "the moving series' path");
    parser.addOption(
        {"series", "The fixed series (id or UID; default the largest volume).", "UID"});
    parser.addOption({"moving-series", "The moving series (id or UID).", "UID"});
    parser.addOption({"affine", "An affine stage (scaling, shear) after the rigid one."});
    parser.addOption(
        {"metric", "mi (Mattes mutual information, default) or ms (mean squares).", "mi|ms", "mi"});
    parser.addOption({"init",
                      "The start: auto (default: the scanner's frame when both series share "
                      "their Frame of Reference, else the centres), centres, or frame.",
                      "auto|centres|frame", "auto"});
    parser.addOption({{"o", "output"}, "The transform as JSON.", "transform.json"});
    parser.addOption({"stats", "Print transform=, init=, metric=, iterations=, seconds=, "
                               "converged= on one line."});
    parser.addOption({"sro",
                      "Also write the registration as a DICOM Spatial Registration object "
                      "(both series DICOM).",
                      "reg.dcm"});
    parser.addHelpOption();
}

// --metric, --init and --affine as options; a message naming the option when one is bad.
std::optional<RegistrationOptions> optionsOf(const QCommandLineParser& parser, QTextStream& err) {
    RegistrationOptions options;
    const QString metric = parser.value("metric");
    if (metric == "ms") {
        options.metric = RegistrationOptions::Metric::MeanSquares;
    } else if (metric != "mi") {
        err << "lucent-cli register: --metric: '" << metric << "' is neither mi nor ms\n";
        return std::nullopt;
    }
    options.affine = parser.isSet("affine");
    const QString init = parser.value("init");
    if (init == "centres") {
        options.initialisation = RegistrationOptions::Initialisation::Centres;
    } else if (init == "frame") {
        options.initialisation = RegistrationOptions::Initialisation::FrameOfReference;
    } else if (init != "auto") {
        err << "lucent-cli register: --init: '" << init << "' is none of auto, centres, frame\n";
        return std::nullopt;
    }
    return options;
}

// The matrix and a summary on stdout (with --stats its key=value line); the JSON document.
// The matrix and the figures on standard output (--stats: one key=value line).
void report(const RegistrationResult& r, const RegistrationOptions& options, bool stats) {
    QTextStream out(stdout);
    out << "fixed -> moving (LPS mm):\n";
    for (int row = 0; row < 4; ++row) {
        for (int c = 0; c < 4; ++c) {
            out << QString("%1").arg(r.fixedToMoving[c][row], 12, 'f', 6);
        }
        out << "\n";
    }
    const char* transform = r.affine ? "affine" : "rigid";
    out << transform << ", started from the " << initialisationName(r.initialisation) << "; metric "
        << metricName(options.metric) << " " << r.metric << ", " << r.iterations << " iterations, "
        << QString::number(r.seconds, 'f', 2) << " s" << (r.converged ? "" : " (not converged)")
        << ": " << QString::fromStdString(r.reason) << "\n";
    if (stats) {
        const bool frame =
            r.initialisation == RegistrationOptions::Initialisation::FrameOfReference;
        out << "transform=" << transform << " init=" << (frame ? "frame" : "centres")
            << " metric=" << r.metric << " iterations=" << r.iterations
            << " seconds=" << QString::number(r.seconds, 'f', 3)
            << " converged=" << (r.converged ? 1 : 0) << "\n";
    }
}

} // namespace

int runRegister(const QStringList& args) {
    QCommandLineParser parser;
    addRegisterOptions(parser);
    QTextStream err(stderr);
    if (!parser.parse(args)) {
        err << "lucent-cli register: " << parser.errorText() << "\n";
        return kUsage;
    }
    if (parser.isSet("help")) {
        QTextStream(stdout) << parser.helpText();
        return kOk;
    }
    const QStringList paths = parser.positionalArguments();
    if (paths.size() != 2 || !parser.isSet("output")) {
        err << "lucent-cli register: expected FIXED MOVING and -o transform.json\n"
            << parser.helpText();
        return kUsage;
    }
    const std::optional<RegistrationOptions> options = optionsOf(parser, err);
    if (!options) {
        return kUsage;
    }
    RegistrationResult r;
    SpatialRegistrationInput sro;
    try {
        const Catalog fixedCatalog = scanPath(paths[0].toStdString());
        const Catalog movingCatalog = scanPath(paths[1].toStdString());
        const SeriesEntry& fixedEntry =
            entryOf(fixedCatalog, parser.value("series").toStdString(), paths[0]);
        const SeriesEntry& movingEntry =
            entryOf(movingCatalog, parser.value("moving-series").toStdString(), paths[1]);
        if (parser.isSet("sro")) {
            sro = spatialRegistrationInput(fixedEntry, movingEntry, glm::dmat4(1.0));
        }
        const Volume fixed = loadSeries(fixedEntry);
        const Volume moving = loadSeries(movingEntry);
        r = registerRigid(fixed, moving, *options);
    } catch (const std::exception& e) {
        err << "lucent-cli register: " << e.what() << "\n";
        return kBadInput;
    }
    report(r, *options, parser.isSet("stats"));
    try {
        writeTransformFile(parser.value("output").toStdString(), r.fixedToMoving,
                           TransformFileFacts{metricName(options->metric), r.metric, r.iterations,
                                              r.seconds, r.converged, r.reason,
                                              r.affine ? "affine" : "rigid",
                                              initialisationName(r.initialisation)});
    } catch (const TransformFileError& e) {
        err << "lucent-cli register: " << e.what() << "\n";
        return kBadInput;
    }
    if (parser.isSet("sro")) {
        sro.fixedToMoving = r.fixedToMoving;
        sro.contentDescription = QString("%1 registration, metric %2 %3, %4 iterations")
                                     .arg(r.affine ? "Affine" : "Rigid")
                                     .arg(metricName(options->metric))
                                     .arg(r.metric)
                                     .arg(r.iterations)
                                     .toStdString();
        try {
            writeSpatialRegistration(parser.value("sro").toStdString(), sro);
        } catch (const std::exception& e) {
            err << "lucent-cli register: " << e.what() << "\n";
            return kBadInput;
        }
    }
    return kOk;
}

} // namespace lucent::cli
