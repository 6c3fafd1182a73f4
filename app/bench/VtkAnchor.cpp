#include "app/bench/VtkAnchor.h"

#include <QFile>
#include <QFileInfo>
#include <QProcess>
#include <QRegularExpression>
#include <QStandardPaths>
#include <QStringList>
#include <QTemporaryDir>

#include <stdexcept>

#include "app/bench/VtkAnchorScript.h"
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
    const std::string missing = " (a benchmark dependency: packaging/install-deps.sh installs it)";
    if (QStandardPaths::findExecutable("xvfb-run").isEmpty()) {
        throw std::runtime_error("VTK anchor: xvfb-run not found: install xvfb and xauth" +
                                 missing);
    }
    if (!QFileInfo(kPython).isExecutable()) {
        throw std::runtime_error(std::string("VTK anchor: ") + kPython + " not found" + missing);
    }
    const Finished probe = runProcess(kPython, {"-c", "import vtk"});
    if (probe.exitCode != 0) {
        throw std::runtime_error("VTK anchor: python3 cannot import vtk: install python3-vtk9" +
                                 missing + ": " + probe.output.toStdString());
    }
}

QString pathText(const std::filesystem::path& p) {
    return QString::fromStdString(p.string());
}

} // namespace

VtkAnchor::VtkAnchor(const Volume& volume, const TransferFunction& preset)
    : dir_(std::make_unique<QTemporaryDir>()) {
    if (!dir_->isValid()) {
        throw std::runtime_error("VTK anchor: cannot make a temporary folder: " +
                                 dir_->errorString().toStdString());
    }
    const std::filesystem::path dir = dir_->path().toStdString();
    volume_ = dir / "anchor.mhd";
    preset_ = dir / "preset.json";
    script_ = dir / "vtk_anchor.py";
    writeMetaImage(volume, volume_);
    writeTransferFunction(preset, preset_);
    QFile script(pathText(script_));
    if (!script.open(QIODevice::WriteOnly) ||
        script.write(kVtkAnchorScript.data(), qint64(kVtkAnchorScript.size())) !=
            qint64(kVtkAnchorScript.size())) {
        throw std::runtime_error("VTK anchor: cannot write " + script_.string());
    }
}

VtkAnchor::~VtkAnchor() = default;

VtkAnchorRun VtkAnchor::run(const std::string& mapper, double unitMm, int width, int height,
                            const std::filesystem::path& png) const {
    requireTools();
    const std::filesystem::path out =
        png.empty() ? std::filesystem::path(dir_->path().toStdString()) / ("vtk_" + mapper + ".png")
                    : png;
    QStringList args = {"-a",
                        "-s",
                        "-screen 0 1280x1024x24",
                        kPython,
                        pathText(script_),
                        "--mapper",
                        QString::fromStdString(mapper),
                        "--size",
                        QStringLiteral("%1x%2").arg(width).arg(height),
                        pathText(volume_),
                        pathText(preset_),
                        pathText(out)};
    if (unitMm > 0.0) {
        args << QString::number(unitMm);
    }
    const Finished finished = runProcess("xvfb-run", args);
    const QRegularExpressionMatch m =
        QRegularExpression(R"(render_ms=([0-9.]+).*gl_renderer=([^\n]*))").match(finished.output);
    if (finished.exitCode != 0 || !m.hasMatch()) {
        throw std::runtime_error("VTK anchor (" + mapper + ") failed, exit code " +
                                 std::to_string(finished.exitCode) + ": " +
                                 finished.output.toStdString());
    }
    return {m.captured(1).toDouble(), readPng(out), m.captured(2).trimmed().toStdString()};
}

} // namespace lucent::bench
