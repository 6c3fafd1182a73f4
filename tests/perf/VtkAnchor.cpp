#include "tests/perf/VtkAnchor.h"

#include <QFileInfo>
#include <QProcess>
#include <QRegularExpression>
#include <QStandardPaths>
#include <QStringList>

#include <stdexcept>

#include "core/formats/MetaImage.h"
#include "core/image/PngIO.h"

namespace lucent::bench {

namespace {

constexpr const char* kPython = "/usr/bin/python3"; // Debian's, where python3-vtk9 lives
constexpr int kTimeoutMs = 15 * 60 * 1000;

struct Finished {
    int exitCode = -1;
    QString output; // stdout and stderr together
};

Finished runProcess(const QString& program, const QStringList& arguments) {
    QProcess p;
    p.setProcessChannelMode(QProcess::MergedChannels);
    p.start(program, arguments);
    if (!p.waitForStarted() || !p.waitForFinished(kTimeoutMs)) {
        p.kill();
        p.waitForFinished();
        throw std::runtime_error("VTK anchor: " + program.toStdString() +
                                 " did not start or did not finish in 15 minutes");
    }
    return {p.exitStatus() == QProcess::NormalExit ? p.exitCode() : -1,
            QString::fromLocal8Bit(p.readAll())};
}

// What the anchor needs, checked before it runs so that a missing package is named.
void requireTools() {
    const QString missing = " (a benchmark dependency: packaging/install-deps.sh installs it)";
    if (QStandardPaths::findExecutable("xvfb-run").isEmpty()) {
        throw std::runtime_error("VTK anchor: xvfb-run not found: install xvfb and xauth" +
                                 missing.toStdString());
    }
    if (!QFileInfo(kPython).isExecutable()) {
        throw std::runtime_error(std::string("VTK anchor: ") + kPython + " not found" +
                                 missing.toStdString());
    }
    const Finished probe = runProcess(kPython, {"-c", "import vtk"});
    if (probe.exitCode != 0) {
        throw std::runtime_error("VTK anchor: python3 cannot import vtk: install python3-vtk9" +
                                 missing.toStdString() + ": " + probe.output.toStdString());
    }
}

} // namespace

std::filesystem::path writeAnchorVolume(const Volume& volume, const std::filesystem::path& dir) {
    const std::filesystem::path mhd = dir / "anchor.mhd";
    writeMetaImage(volume, mhd);
    return mhd;
}

VtkAnchorRun runVtkAnchor(const std::filesystem::path& mhd, const std::string& mapper,
                          double unitMm, const std::filesystem::path& png) {
    requireTools();
    const QString source = LUCENT_SOURCE_DIR;
    QStringList args = {"-a",
                        "-s",
                        "-screen 0 1280x1024x24",
                        kPython,
                        source + "/tests/perf/vtk_anchor.py",
                        "--mapper",
                        QString::fromStdString(mapper),
                        QString::fromStdString(mhd.string()),
                        source + "/resources/presets/ct-bone.json",
                        QString::fromStdString(png.string())};
    if (unitMm > 0.0) {
        args << QString::number(unitMm);
    }
    const Finished run = runProcess("xvfb-run", args);
    const QRegularExpressionMatch m =
        QRegularExpression(R"(render_ms=([0-9.]+))").match(run.output);
    if (run.exitCode != 0 || !m.hasMatch()) {
        throw std::runtime_error("VTK anchor (" + mapper + ") failed, exit code " +
                                 std::to_string(run.exitCode) + ": " + run.output.toStdString());
    }
    return {m.captured(1).toDouble(), readPng(png)};
}

} // namespace lucent::bench
