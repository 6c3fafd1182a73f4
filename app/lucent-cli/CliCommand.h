#pragma once

#include <QCommandLineParser>
#include <QStringList>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

// Exit status of every lucent-cli command: 0 ok, 2 usage, 3 nothing loadable or bad input.
namespace lucent::cli {

constexpr int kOk = 0;
constexpr int kUsage = 2;
constexpr int kBadInput = 3;
constexpr int kNetwork = 4; // a PACS, a render server or the network failed

// A command line a command cannot take: the command exits kUsage with the message.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The number given with --name, or `fallback` when the flag is absent. Throws
// UsageError naming the flag when the text is not a number.
inline double numberFlag(const QCommandLineParser& p, const QString& name, double fallback) {
    if (!p.isSet(name)) {
        return fallback;
    }
    bool ok = false;
    const double v = p.value(name).toDouble(&ok);
    if (!ok) {
        throw UsageError("--" + name.toStdString() + ": '" + p.value(name).toStdString() +
                         "' is not a number");
    }
    return v;
}

// Each takes the arguments after the command name, with the program name first.
int runInfo(const QStringList& args);
int runConvert(const QStringList& args);
int runCompare(const QStringList& args);
int runRender(const QStringList& args);
int runPacs(const QStringList& args);     // exit 4: the PACS or the network failed
int runPacsSend(const QStringList& args); // pacs send: C-STORE or STOW-RS
int runExport(const QStringList& args);   // DICOM to a folder or ZIP, de-identified or not
int runBench(const QStringList& args);
// bench lod PATH: PSNR against the GPU budget, per-brick levels and one level.
int runLodBench(const QStringList& args);
// bench interactive PATH: issue 31's goal table, VTK and VolPack side by side.
int runInteractiveBench(const QStringList& args);
int runOptions(const QStringList& args);      // the render options table
int runSurface(const QStringList& args);      // isosurface meshes and the method of spheres
int runMeasurements(const QStringList& args); // a series' or an SR's measurements
int runMovie(const QStringList& args);        // turntable or cine movies (MP4, WebM, GIF)
int runHang(const QStringList& args);         // hanging protocols: which series goes where
int runRegister(const QStringList& args);     // rigid registration of two series (ITK)
int runSegment(const QStringList& args);      // a segment by threshold, islands and margin
int runSegmentStats(const QStringList& args); // statistics of a labelmap's labels

} // namespace lucent::cli
