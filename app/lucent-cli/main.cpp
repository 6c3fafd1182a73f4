#include <QCoreApplication>
#include <QGuiApplication>

#include <QTextStream>
#include <memory>

#include "CliCommand.h"

namespace {

const char* kUsageText =
    "usage: lucent-cli COMMAND ...\n"
    "  info PATH [--json]                   what PATH holds: series, geometry, warnings\n"
    "  convert PATH OUT.mhd [--series UID]  write one series as MetaImage (.mhd + .raw)\n"
    "  render PATH -o OUT.png [options]     volume rendering (CPU, GL or a server); --help "
    "lists options\n"
    "  compare A.png B.png                  print psnr_db=<x> ssim=<y> for two images\n"
    "  surface PATH -o OUT.stl|ply|vtk|obj --iso HU [--svr-radius MM] [...]\n"
    "                                       isosurface mesh, local surface-to-volume ratio\n"
    "  segment PATH --threshold LO,HI [--keep-largest | --min-island-mm3 N] [--margin MM]\n"
    "          [--name NAME] -o OUT.nii[.gz]|OUT.dcm [--stats] [--surface MESH.stl|ply|obj]\n"
    "                                       a segment as a NIfTI labelmap or a DICOM SEG\n"
    "                                       (and its surface)\n"
    "  segment-stats PATH LABELS.nii[.gz]|SEG.dcm  mL, HU, area, diameter of each label/segment\n"
    "  movie PATH -o OUT.mp4|webm|gif [--turntable DEG | --cine-axis i|j|k] [--frames N]\n"
    "        [--fps N] [--size WxH] [options]  turntable or cine movie (FFmpeg)\n"
    "  options [--markdown]                 every render option: flag, wire key, range, default\n"
    "  bench quality PATH [--backend cpu|gl] [--csv OUT.csv] [--plot OUT.png]\n"
    "                                       time against PSNR/SSIM of every sampling setting\n"
    "  bench lod PATH [--budgets MIB,...] [--csv OUT.csv] [--plot OUT.png]\n"
    "                                       PSNR against the GPU budget, per-brick and one level\n"
    "  bench interactive PATH [--runs N] [--no-anchors] [--csv OUT.csv] [--size WxH] [...]\n"
    "                                       issue 31's goal table, VTK and VolPack side by side\n"
    "PATH: a DICOM folder (searched recursively), a DICOM file, a DICOMDIR,\n"
    "      or a .mhd/.mha, .nii/.nii.gz or InVesalius .inv3 volume.\n"
    "  pacs echo|find|get --pacs AET@HOST:PORT ...  C-ECHO, C-FIND, C-GET into the study store\n"
    "  pacs send (--pacs AET@HOST:PORT | --stow URL) PATH [--series UID]\n"
    "                                       C-STORE or STOW-RS of the instances under PATH\n"
    "  export PATH -o OUT|OUT.zip [--series UID] [--anonymize] [--dicomdir]\n"
    "                                       copy instances out, de-identified or not\n"
    "  measurements (--series UID [--store DIR] | SR_FILE [--images DIR]) [--json]\n"
    "                                       measurements saved as DICOM SR, and what is not shown\n"
    "  measurements --patient ID [--store DIR] --recist [--json]\n"
    "                                       RECIST 1.1 follow-up: lesions by timepoint, sums,\n"
    "                                       change from baseline and nadir, response\n"
    "  hang PATH... [--protocol NAME] [--protocols DIR] [--json]\n"
    "                                       the hanging protocol that wins, which series goes "
    "where\n"
    "  register FIXED MOVING -o transform.json [--series UID] [--moving-series UID]\n"
    "           [--metric mi|ms] [--stats]  rigid registration: fixed LPS mm -> moving LPS mm\n"
    "Exit status: 0 ok, 2 usage, 3 nothing loadable or bad input, 4 PACS or network failure.\n";

} // namespace

int main(int argc, char** argv) {
    // The bench draws a plot with text: fonts need a GUI application (offscreen, no display).
    const bool gui = argc > 1 && std::string_view(argv[1]) == "bench";
    if (gui && qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) {
        qputenv("QT_QPA_PLATFORM", "offscreen");
    }
    const std::unique_ptr<QCoreApplication> app =
        gui ? std::make_unique<QGuiApplication>(argc, argv)
            : std::make_unique<QCoreApplication>(argc, argv);
    QCoreApplication::setApplicationName("lucent-cli");
    QCoreApplication::setApplicationVersion(LUCENT_VERSION);
    QStringList args = QCoreApplication::arguments();
    QTextStream err(stderr);
    if (args.size() < 2) {
        err << kUsageText;
        return lucent::cli::kUsage;
    }
    const QString command = args.takeAt(1);
    if (command == "--help" || command == "-h" || command == "help") {
        QTextStream(stdout) << kUsageText;
        return lucent::cli::kOk;
    }
    if (command == "--version") {
        QTextStream(stdout) << "lucent-cli " << LUCENT_VERSION << "\n";
        return lucent::cli::kOk;
    }
    if (command == "info") {
        return lucent::cli::runInfo(args);
    }
    if (command == "convert") {
        return lucent::cli::runConvert(args);
    }
    if (command == "export") {
        return lucent::cli::runExport(args);
    }
    if (command == "pacs") {
        return lucent::cli::runPacs(args);
    }
    if (command == "render") {
        return lucent::cli::runRender(args);
    }
    if (command == "bench") {
        return lucent::cli::runBench(args);
    }
    if (command == "options") {
        return lucent::cli::runOptions(args);
    }
    if (command == "surface") {
        return lucent::cli::runSurface(args);
    }
    if (command == "measurements") {
        return lucent::cli::runMeasurements(args);
    }
    if (command == "movie") {
        return lucent::cli::runMovie(args);
    }
    if (command == "register") {
        return lucent::cli::runRegister(args);
    }
    if (command == "segment") {
        return lucent::cli::runSegment(args);
    }
    if (command == "segment-stats") {
        return lucent::cli::runSegmentStats(args);
    }
    if (command == "hang") {
        return lucent::cli::runHang(args);
    }
    if (command == "compare") {
        return lucent::cli::runCompare(args);
    }
    err << "lucent-cli: unknown command '" << command << "'\n" << kUsageText;
    return lucent::cli::kUsage;
}
