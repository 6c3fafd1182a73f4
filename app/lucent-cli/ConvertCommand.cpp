// lucent-cli convert PATH OUT.mhd [--series UID]
#include <QCommandLineParser>
#include <QTextStream>

#include "CliCommand.h"
#include "TerminalProgress.h"
#include "core/formats/MetaImage.h"
#include "core/io/Catalog.h"

namespace lucent::cli {

int runConvert(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription("Writes one series as a MetaImage (.mhd + .raw).");
    parser.addPositionalArgument("PATH", "DICOM folder, file or DICOMDIR, or a volume file");
    parser.addPositionalArgument("OUT.mhd",
                                 "the MetaImage header to write; the .raw goes beside it");
    parser.addOption({"series", "Series id or UID (default: the largest volume).", "UID"});
    parser.addHelpOption();
    QTextStream err(stderr);
    if (!parser.parse(args)) {
        err << "lucent-cli convert: " << parser.errorText() << "\n";
        return kUsage;
    }
    if (parser.isSet("help")) {
        QTextStream(stdout) << parser.helpText();
        return kOk;
    }
    const QStringList positional = parser.positionalArguments();
    if (positional.size() != 2 || !positional[1].endsWith(".mhd", Qt::CaseInsensitive)) {
        err << "lucent-cli convert: expected PATH and an OUT.mhd file name\n" << parser.helpText();
        return kUsage;
    }
    const TerminalProgress progress;
    try {
        const Volume volume = loadPath(positional[0].toStdString(),
                                       parser.value("series").toStdString(), progress.control());
        progress.finish();
        writeMetaImage(volume, positional[1].toStdString());
        const glm::ivec3 d = volume.dims();
        QTextStream(stdout) << "wrote " << positional[1] << " (" << d.x << "x" << d.y << "x" << d.z
                            << " " << voxelTypeName(volume.type()) << ")\n";
        for (const std::string& w : volume.warnings) {
            err << "warning: " << QString::fromStdString(w) << "\n";
        }
    } catch (const std::exception& e) {
        progress.finish();
        err << "lucent-cli convert: " << e.what() << "\n";
        return kBadInput;
    }
    return kOk;
}

} // namespace lucent::cli
