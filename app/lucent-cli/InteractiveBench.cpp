// lucent-cli bench interactive PATH: issue 31's goal table ("Interactive at full quality"),
// with the VTK and VolPack anchors run side by side in the same run: a markdown table on
// stdout (what, Lucent, anchor, ratio, goal, met), the GL renderer and the CPU threads it ran
// on, and the rows as CSV with --csv. The rows are InteractiveRows.h's.
#include <QCommandLineParser>
#include <QFile>
#include <QRegularExpression>
#include <QTextStream>

#include "CliCommand.h"
#include "InteractiveRows.h"
#include "TerminalProgress.h"
#include "app/bench/VtkAnchor.h"
#include "core/io/Catalog.h"
#include "core/raycast/CpuRayCaster.h"
#include "core/scene/RenderOptions.h"
#include "render/OffscreenContext.h"

namespace lucent::cli {

namespace {

void addOptions(QCommandLineParser& parser) {
    parser.addPositionalArgument("interactive", "The bench to run (interactive).");
    parser.addPositionalArgument("PATH", "DICOM folder, file or DICOMDIR, or a volume file");
    parser.addOptions({
        {"series", "Series id or UID (default: the largest volume).", "UID"},
        {"size", "Image size of the scene and the anchors (default 512x512).", "WxH", "512x512"},
        {"cube", "Side of the tiled cube (default 512).", "N", "512"},
        {"cube-size", "Image size of the cube's rows (default 1024x1024).", "WxH", "1024x1024"},
        {"long-dims", "The long tiled volume (default 512x512x5382).", "WxHxD", "512x512x5382"},
        {"long-budget", "Its GPU budget in MiB (default 2048).", "MIB", "2048"},
        {"skip-large", "Leave out the long volume."},
        {"surface-triangles", "Triangles of the surface (default 700000).", "N", "700000"},
        {"surface-iso", "Iso value of the surface (default 300).", "VALUE", "300"},
        {"runs", "Runs of Lucent against the anchors (default 3).", "N", "3"},
        {"units", "Opacity units: voxel, mm or both (default voxel,mm).", "LIST", "voxel,mm"},
        {"no-anchors", "Leave out VTK and VolPack."},
        {"csv", "Write the rows as CSV.", "OUT.csv"},
    });
    parser.addHelpOption();
}

int positiveInt(const QCommandLineParser& p, const QString& name) {
    bool ok = false;
    const int v = p.value(name).toInt(&ok);
    if (!ok || v < 1) {
        throw UsageError("--" + name.toStdString() + ": '" + p.value(name).toStdString() +
                         "' is not a whole number above 0");
    }
    return v;
}

glm::ivec2 imageSize(const QCommandLineParser& p, const QString& name) {
    try {
        const auto [w, h] = parseImageSize(p.value(name).toStdString());
        return {w, h};
    } catch (const std::invalid_argument& e) {
        throw UsageError("--" + name.toStdString() + ": " + e.what());
    }
}

glm::ivec3 volumeDims(const QCommandLineParser& p, const QString& name) {
    const auto m = QRegularExpression(R"(^(\d+)x(\d+)x(\d+)$)").match(p.value(name));
    const glm::ivec3 d = m.hasMatch() ? glm::ivec3(m.captured(1).toInt(), m.captured(2).toInt(),
                                                   m.captured(3).toInt())
                                      : glm::ivec3(0);
    if (d.x < 1 || d.y < 1 || d.z < 1) {
        throw UsageError("--" + name.toStdString() + ": '" + p.value(name).toStdString() +
                         "' is not WxHxD voxels");
    }
    return d;
}

std::vector<double> opacityUnits(const QCommandLineParser& p) {
    std::vector<double> units;
    for (const QString& u : p.value("units").split(',')) {
        if (u != "voxel" && u != "mm") {
            throw UsageError("--units: '" + u.toStdString() + "' is neither voxel nor mm");
        }
        units.push_back(u == "mm" ? 1.0 : 0.0);
    }
    return units;
}

InteractiveSettings settingsOf(const QCommandLineParser& p) {
    InteractiveSettings s;
    s.size = imageSize(p, "size");
    s.cube = positiveInt(p, "cube");
    s.cubeSize = imageSize(p, "cube-size");
    s.longDims = volumeDims(p, "long-dims");
    s.longBudgetBytes = std::size_t(positiveInt(p, "long-budget")) << 20;
    s.skipLarge = p.isSet("skip-large");
    s.surfaceTriangles = std::size_t(positiveInt(p, "surface-triangles"));
    s.surfaceIso = numberFlag(p, "surface-iso", 300.0);
    s.runs = positiveInt(p, "runs");
    s.unitsMm = opacityUnits(p);
    s.anchors = !p.isSet("no-anchors");
    return s;
}

InteractiveDevices openDevices(const Volume& volume, const InteractiveSettings& s) {
    InteractiveDevices devices;
    try {
        devices.gl = OffscreenContext::create();
    } catch (const std::exception& e) {
        devices.glMissing = std::string("no GL device: ") + e.what();
    }
    devices.vtkMissing = "skipped (--no-anchors)";
    if (s.anchors) {
        try {
            devices.vtk = std::make_unique<bench::VtkAnchor>(volume, loadPreset("ct-bone"));
            devices.vtkMissing.clear();
        } catch (const std::exception& e) {
            devices.vtkMissing = std::string("not run: ") + e.what();
        }
    }
    return devices;
}

// The lines above the table: the scene, the GL renderer, the CPU threads.
void printHeader(QTextStream& out, const QString& path, const Volume& volume,
                 const InteractiveDevices& devices) {
    const glm::ivec3 n = volume.dims();
    out << "# bench interactive: "
        << (volume.description.empty() ? path : QString::fromStdString(volume.description)) << ", "
        << n.x << "x" << n.y << "x" << n.z
        << ", ct-bone, shading, trilinear unless said, step 0.5, anterior camera, "
           "6 frames turning 5 degrees (median)\n";
    if (devices.gl) {
        const QString gl = QString::fromStdString(devices.gl->description());
        out << "GL renderer: " << gl
            << (gl.contains("llvmpipe") || gl.contains("softpipe")
                    ? " (a software rasteriser on the CPU: these are not a GPU's figures)"
                    : "")
            << "\n";
    } else {
        out << "GL renderer: none (" << QString::fromStdString(devices.glMissing) << ")\n";
    }
    // CpuRayCaster::device(): "cpu: N threads".
    out << "CPU caster: " << QString::fromStdString(CpuRayCaster(volume).device()).mid(5)
        << " (VTK fixed-point: 2 threads; VolPack: 1)\n\n";
}

QString markdownCell(const std::string& text) {
    return QString::fromStdString(text).replace('|', "\\|");
}

QString csvCell(const std::string& text) {
    return '"' + QString::fromStdString(text).replace('"', "\"\"") + '"';
}

void printTable(QTextStream& out, const InteractiveRows& rows) {
    out << "| what | Lucent | anchor | ratio | goal | met |\n|---|---|---|---|---|---|\n";
    for (const InteractiveRow& r : rows) {
        out << "| " << markdownCell(r.what) << " | " << markdownCell(r.lucent) << " | "
            << markdownCell(r.anchor) << " | " << markdownCell(r.ratio) << " | "
            << markdownCell(r.goal) << " | " << markdownCell(r.met) << " |\n";
    }
}

void writeCsv(const QString& path, const InteractiveRows& rows) {
    QFile f(path);
    if (!f.open(QIODevice::WriteOnly | QIODevice::Truncate)) {
        throw std::runtime_error("cannot write " + path.toStdString());
    }
    QTextStream csv(&f);
    csv << "what,lucent,anchor,ratio,goal,met\n";
    for (const InteractiveRow& r : rows) {
        csv << csvCell(r.what) << "," << csvCell(r.lucent) << "," << csvCell(r.anchor) << ","
            << csvCell(r.ratio) << "," << csvCell(r.goal) << "," << csvCell(r.met) << "\n";
    }
}

InteractiveRows measureRows(const Volume& volume, const InteractiveSettings& s,
                            const InteractiveDevices& devices) {
    using Group =
        InteractiveRows (*)(const Volume&, const InteractiveSettings&, const InteractiveDevices&);
    const std::pair<const char*, Group> groups[] = {
        {"the tiled cube", glCubeRows},
        {"the long volume", glLongRows},
        {"the surface", glSurfaceRows},
        {"Lucent against the anchors", anchorRows},
        {"memory and the time outside the cast", defaultPathRows},
    };
    QTextStream err(stderr);
    InteractiveRows rows;
    for (const auto& [name, group] : groups) {
        err << "bench interactive: " << name << "\n" << Qt::flush;
        const InteractiveRows part = group(volume, s, devices);
        rows.insert(rows.end(), part.begin(), part.end());
    }
    return rows;
}

} // namespace

int runInteractiveBench(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(
        "bench interactive PATH: issue 31's goal table, with VTK and VolPack side by side.");
    addOptions(parser);
    QTextStream err(stderr), out(stdout);
    if (!parser.parse(args)) {
        err << "lucent-cli bench interactive: " << parser.errorText() << "\n";
        return kUsage;
    }
    if (parser.isSet("help")) {
        out << parser.helpText();
        return kOk;
    }
    InteractiveSettings settings;
    try {
        if (parser.positionalArguments().size() != 2) {
            throw UsageError("expected 'interactive PATH'");
        }
        settings = settingsOf(parser);
    } catch (const UsageError& e) {
        err << "lucent-cli bench interactive: " << e.what() << "\n";
        return kUsage;
    }
    const QString path = parser.positionalArguments()[1];
    try {
        Volume volume;
        {
            const TerminalProgress progress;
            volume = loadPath(path.toStdString(), parser.value("series").toStdString(),
                              progress.control());
            progress.finish();
        }
        const InteractiveDevices devices = openDevices(volume, settings);
        const InteractiveRows rows = measureRows(volume, settings, devices);
        printHeader(out, path, volume, devices);
        printTable(out, rows);
        if (parser.isSet("csv")) {
            writeCsv(parser.value("csv"), rows);
        }
    } catch (const std::exception& e) {
        err << "lucent-cli bench interactive: " << e.what() << "\n";
        return kBadInput;
    }
    return kOk;
}

} // namespace lucent::cli
