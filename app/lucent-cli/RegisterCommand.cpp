// lucent-cli register FIXED MOVING [--series UID] [--moving-series UID] [--affine]
//                     [--metric mi|ms] -o transform.json [--stats]
// Rigid registration of two series (core/registration): the 4x4 matrix that maps a point
// in the fixed series' LPS mm to the same anatomy in the moving series' LPS mm.
#include <QCommandLineParser>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTextStream>

#include "CliCommand.h"
#include "core/io/Catalog.h"
#include "core/registration/Registration.h"

namespace lucent::cli {

int runRegister(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(
        "Rigid registration (versor rigid, ITK) of MOVING onto FIXED. Writes the 4x4 matrix "
        "that maps fixed LPS mm to moving LPS mm (row-major rows) with the metric, iterations "
        "and seconds.");
    parser.addPositionalArgument("FIXED", "the fixed series' path (DICOM folder, file, ...)");
    parser.addPositionalArgument("MOVING", "the moving series' path");
    parser.addOption(
        {"series", "The fixed series (id or UID; default the largest volume).", "UID"});
    parser.addOption({"moving-series", "The moving series (id or UID).", "UID"});
    parser.addOption({"affine", "An affine stage after the rigid one (not implemented yet)."});
    parser.addOption(
        {"metric", "mi (Mattes mutual information, default) or ms (mean squares).", "mi|ms", "mi"});
    parser.addOption({{"o", "output"}, "The transform as JSON.", "transform.json"});
    parser.addOption({"stats", "Print metric=, iterations=, seconds= on one line."});
    parser.addHelpOption();
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
    RegistrationOptions options;
    const QString metric = parser.value("metric");
    if (metric == "ms") {
        options.metric = RegistrationOptions::Metric::MeanSquares;
    } else if (metric != "mi") {
        err << "lucent-cli register: --metric: '" << metric << "' is neither mi nor ms\n";
        return kUsage;
    }
    if (parser.isSet("affine")) {
        err << "lucent-cli register: --affine: the affine stage is not implemented yet\n";
        return kUsage;
    }
    RegistrationResult r;
    try {
        const Volume fixed = loadPath(paths[0].toStdString(), parser.value("series").toStdString());
        const Volume moving =
            loadPath(paths[1].toStdString(), parser.value("moving-series").toStdString());
        r = registerRigid(fixed, moving, options);
    } catch (const std::exception& e) {
        err << "lucent-cli register: " << e.what() << "\n";
        return kBadInput;
    }
    QJsonArray rows;
    QTextStream out(stdout);
    out << "fixed -> moving (LPS mm):\n";
    for (int row = 0; row < 4; ++row) {
        QJsonArray values;
        for (int c = 0; c < 4; ++c) {
            values.append(r.fixedToMoving[c][row]);
            out << QString("%1").arg(r.fixedToMoving[c][row], 12, 'f', 6);
        }
        out << "\n";
        rows.append(values);
    }
    out << "metric " << metricName(options.metric) << " " << r.metric << ", " << r.iterations
        << " iterations, " << QString::number(r.seconds, 'f', 2) << " s"
        << (r.converged ? "" : " (not converged)") << ": " << QString::fromStdString(r.reason)
        << "\n";
    if (parser.isSet("stats")) {
        out << "metric=" << r.metric << " iterations=" << r.iterations
            << " seconds=" << QString::number(r.seconds, 'f', 3)
            << " converged=" << (r.converged ? 1 : 0) << "\n";
    }
    const QJsonObject root{{"matrix", rows},
                           {"convention", "fixed LPS mm -> moving LPS mm, row-major rows"},
                           {"metric_name", metricName(options.metric)},
                           {"metric", r.metric},
                           {"iterations", r.iterations},
                           {"seconds", r.seconds},
                           {"converged", r.converged},
                           {"reason", QString::fromStdString(r.reason)}};
    QFile file(parser.value("output"));
    if (!file.open(QIODevice::WriteOnly) ||
        file.write(QJsonDocument(root).toJson(QJsonDocument::Indented)) < 0) {
        err << "lucent-cli register: cannot write " << parser.value("output") << "\n";
        return kBadInput;
    }
    return kOk;
}

} // namespace lucent::cli
