// lucent-cli convert PATH OUT.mhd [--series UID]
//                    [--overlay PATH [--overlay-series UID] [--transform transform.json]]
#include <QCommandLineParser>
#include <QTextStream>

#include "CliCommand.h"
#include "OverlayFlags.h"
#include "TerminalProgress.h"
#include "core/formats/MetaImage.h"
#include "core/fusion/OverlayResampler.h"
#include "core/io/Catalog.h"

namespace lucent::cli {

int runConvert(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(
        "Writes one series as a MetaImage (.mhd + .raw). With --overlay, writes the overlay "
        "series resampled onto that series' grid instead (Float32, trilinear; where the "
        "overlay has no value, its lowest value).");
    parser.addPositionalArgument("PATH", "DICOM folder, file or DICOMDIR, or a volume file");
    parser.addPositionalArgument("OUT.mhd",
                                 "the MetaImage header to write; the .raw goes beside it");
    parser.addOption({"series", "Series id or UID (default: the largest volume).", "UID"});
    addOverlayFlags(parser);
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
        Volume volume = loadPath(positional[0].toStdString(), parser.value("series").toStdString(),
                                 progress.control());
        if (parser.isSet("overlay")) {
            // Outside the overlay: its lowest value (air, no uptake), which every reader
            // of a MetaImage takes, where NaN is not.
            const Volume overlay =
                loadPath(parser.value("overlay").toStdString(),
                         parser.value("overlay-series").toStdString(), progress.control());
            volume =
                resampleOverlay(overlay, volume.geometry(), baseToOverlay(parser, volume, overlay),
                                float(overlay.valueRange().first));
        } else if (parser.isSet("overlay-series") || parser.isSet("transform")) {
            progress.finish();
            err << "lucent-cli convert: --overlay-series and --transform need --overlay PATH\n";
            return kUsage;
        }
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
