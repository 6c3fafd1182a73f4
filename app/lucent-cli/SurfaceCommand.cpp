// lucent-cli surface PATH -o OUT.(stl|ply|vtk|obj) --iso HU [...]: the
// isosurface of a volume as a closed mesh, cleaned up, with the method of
// spheres' surface-to-volume field (docs/surfaces.md).
#include <QCommandLineParser>
#include <QTextStream>

#include <cmath>
#include <cstdio>

#include "CliCommand.h"
#include "TerminalProgress.h"
#include "core/formats/MeshFiles.h"
#include "core/io/Catalog.h"
#include "core/scene/RenderOptions.h"
#include "core/surface/FieldStats.h"
#include "core/surface/SurfacePipeline.h"

namespace lucent::cli {
namespace {

SurfaceRequest requestOf(const QCommandLineParser& p) {
    if (!p.isSet("iso")) {
        throw UsageError("--iso VALUE is required (HU for CT)");
    }
    if (p.isSet("min-component-voxels") && p.isSet("largest")) {
        throw UsageError("--min-component-voxels and --largest exclude each other");
    }
    SurfaceRequest r;
    r.iso = numberFlag(p, "iso", 0.0);
    if (p.isSet("clip")) {
        r.clip = parseClipBox(p.value("clip").toStdString());
    }
    r.maskSigma = numberFlag(p, "smooth-mask", 0.0);
    r.minComponentVoxels = numberFlag(p, "min-component-voxels", 0.0);
    const double largest = numberFlag(p, "largest", 0.0);
    if (largest < 0.0 || largest != std::floor(largest)) {
        throw UsageError("--largest must be a whole number of parts");
    }
    r.keepLargest = std::size_t(largest);
    const double iterations = numberFlag(p, "smooth", 0.0);
    if (iterations != std::floor(iterations)) {
        throw UsageError("--smooth must be a whole number of iterations");
    }
    r.smoothIterations = int(iterations);
    r.decimate = numberFlag(p, "decimate", 0.0);
    r.svrRadius = numberFlag(p, "svr-radius", 0.0);
    return r;
}

std::string fixed(double v, int digits) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, v);
    return text;
}

std::string statsOf(const SurfaceResult& s) {
    const MeshReport& m = s.report;
    std::string line =
        "triangles=" + std::to_string(m.triangles) + " vertices=" + std::to_string(m.vertices) +
        " area_mm2=" + fixed(m.area, 1) + " volume_mm3=" + fixed(m.volume, 1) +
        " watertight=" + (m.closedManifold() ? "1" : "0") +
        " components=" + std::to_string(m.components) +
        " components_dropped=" + std::to_string(s.componentsDropped) +
        " h_max_mm=" + fixed(m.hMax, 3) + " mesh_bytes_per_triangle=" +
        fixed(double(s.mesh.vertices.size() * sizeof(glm::dvec3) +
                     s.mesh.triangles.size() * sizeof(glm::u32vec3)) /
                  double(m.triangles),
              1) +
        " extract_ms=" + fixed(s.extractMs, 1) + " cleanup_ms=" + fixed(s.cleanupMs, 1);
    if (s.svr) {
        line += " svr_radius_mm=" + fixed(s.svr->radius, 3) +
                " h_max_over_r=" + fixed(s.svr->longestEdgeOverRadius, 3) +
                " svr_ms=" + fixed(s.svrMs, 1) + " " + statsLine("svr", fieldStats(s.svr->svr)) +
                " svr_global=" + fixed(s.svr->totalRatio, 6) +
                " svr_candidates_per_vertex=" + fixed(s.svr->candidatesPerQuery, 1) +
                " svr_clipped_per_vertex=" + fixed(s.svr->clippedPerQuery, 1) +
                " svr_index_bytes_per_triangle=" +
                fixed(double(s.svr->indexBytes) / double(m.triangles), 1) +
                " svr_threads=" + std::to_string(s.svr->threads);
    }
    return line;
}

} // namespace

int runSurface(const QStringList& args) {
    QCommandLineParser parser;
    parser.setApplicationDescription(
        "The isosurface of a volume as a closed triangle mesh (LPS mm), with the method of "
        "spheres' local surface-to-volume ratio. Writes STL, PLY, VTK or OBJ.");
    parser.addPositionalArgument("PATH", "DICOM folder, file or DICOMDIR, or a volume file");
    parser.addOptions({
        {{"o", "output"}, "The mesh file: .stl, .ply, .vtk or .obj.", "OUT"},
        {"iso", "Iso value (HU for CT); a voxel >= it is inside.", "VALUE"},
        {"series", "Series id or UID (default: the largest volume).", "UID"},
        {"clip", "Clip box in voxel indices; outside counts as outside.", "X0,Y0,Z0,X1,Y1,Z1"},
        {"smooth-mask", "Gaussian pre-smoothing in voxels, for binary masks.", "SIGMA"},
        {"min-component-voxels", "Drop parts enclosing less than N voxels' volume.", "N"},
        {"largest", "Keep the K largest parts (by triangles).", "K"},
        {"smooth", "Windowed-sinc smoothing iterations (no shrinkage).", "ITER"},
        {"decimate", "Remove this fraction of the triangles (0 to 1).", "F"},
        {"svr-radius",
         "Surface-to-volume ratio at every vertex for balls of this radius "
         "(written to PLY, VTK and OBJ).",
         "MM"},
        {"stats", "Print the figures on one line."},
    });
    parser.addHelpOption();
    QTextStream err(stderr);
    if (!parser.parse(args)) {
        err << "lucent-cli surface: " << parser.errorText() << "\n";
        return kUsage;
    }
    if (parser.isSet("help")) {
        QTextStream(stdout) << parser.helpText();
        return kOk;
    }
    if (parser.positionalArguments().size() != 1 || !parser.isSet("output")) {
        err << "lucent-cli surface: expected PATH and -o OUT\n" << parser.helpText();
        return kUsage;
    }
    SurfaceRequest request;
    MeshFormat format = MeshFormat::Stl;
    try {
        request = requestOf(parser);
        format = meshFormatOf(parser.value("output").toStdString());
    } catch (const std::exception& e) { // UsageError, and std::invalid_argument of the clip box
        err << "lucent-cli surface: " << e.what() << "\n";
        return kUsage;
    }
    const TerminalProgress progress;
    try {
        const Volume volume = loadPath(parser.positionalArguments()[0].toStdString(),
                                       parser.value("series").toStdString(), progress.control());
        progress.finish();
        const SurfaceResult surface = makeSurface(volume, request);
        for (const std::string& w : surface.warnings) {
            err << "warning: " << QString::fromStdString(w) << "\n";
        }
        const MeshFileContent content = surfaceFileContent(surface, request.iso);
        if (surface.svr && format == MeshFormat::Stl) {
            err << "lucent-cli surface: STL holds no per-vertex values; write .ply, .vtk or "
                   ".obj to keep the surface-to-volume field\n";
        }
        writeMesh(surface.mesh, parser.value("output").toStdString(), format, content);
        if (parser.isSet("stats")) {
            QTextStream(stdout) << QString::fromStdString(statsOf(surface)) << "\n";
        }
    } catch (const std::exception& e) {
        progress.finish();
        err << "lucent-cli surface: " << e.what() << "\n";
        return kBadInput;
    }
    return kOk;
}

} // namespace lucent::cli
