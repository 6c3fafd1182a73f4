#pragma once
// Mesh files (docs/surfaces.md): binary STL for printing, binary PLY with
// normals and the SVR field (as a float property and as baked viridis
// colours), legacy VTK with point data (opens coloured in 3D Slicer and
// ParaView), and OBJ. Every header states SPACE=LPS and millimetres (3D
// Slicer's convention). Written atomically: a file appears complete or not at
// all, and a file already there is left as it was when writing fails.

#include <filesystem>
#include <string>
#include <vector>

#include "core/surface/SurfacePipeline.h"
#include "core/surface/TriangleMesh.h"

namespace lucent {

enum class MeshFormat { Stl, Ply, Vtk, Obj };

// By the extension (.stl, .ply, .vtk, .obj; any case). Throws
// std::invalid_argument naming the file and the extensions known.
MeshFormat meshFormatOf(const std::filesystem::path& file);

// What a file holds besides the geometry.
struct MeshFileContent {
    // A line for the header ("Lucent 0.4 iso=300HU"): STL's 80-byte header
    // (cut to fit; never starting with "solid"), a comment elsewhere.
    std::string description;
    // Per vertex (empty: none): written to PLY (property `svr`, MeshLab's
    // `quality`, and viridis colours over [colourLo, colourHi]), VTK (point
    // scalars `svr`) and OBJ (vertex colours, the common extension).
    std::vector<float> svr;
    double svrRadiusMm = 0.0;
    double colourLo = 0.0, colourHi = 1.0;
};

// What a file of a computed surface holds: "iso=300.0 svr_radius_mm=5.000",
// and its field coloured over the field's 5th to 95th percentile (the
// display's range, surfaceFieldRange()).
MeshFileContent surfaceFileContent(const SurfaceResult& surface, double iso);

// Writes `mesh` as `format` to `file`. Throws std::runtime_error naming the
// file when it cannot be written (a missing folder, no permission, a full
// disk), std::invalid_argument for an empty mesh or an svr of the wrong size.
void writeMesh(const TriangleMesh& mesh, const std::filesystem::path& file, MeshFormat format,
               const MeshFileContent& content = {});

} // namespace lucent
