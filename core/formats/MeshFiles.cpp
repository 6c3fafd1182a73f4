#include "core/formats/MeshFiles.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <ostream>
#include <stdexcept>
#include <tuple>

#include "core/formats/AtomicFile.h"
#include "core/image/ColourMap.h"
#include "core/surface/VertexNormals.h"

namespace lucent {
namespace {

// Little-endian (STL, PLY) or big-endian (legacy VTK) binary numbers.
template <class T> void put(std::ostream& out, T value, std::endian order) {
    auto bytes = std::bit_cast<std::array<char, sizeof(T)>>(value);
    if (order != std::endian::native) {
        std::reverse(bytes.begin(), bytes.end());
    }
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

void putVec(std::ostream& out, const glm::dvec3& v, std::endian order) {
    put(out, float(v.x), order);
    put(out, float(v.y), order);
    put(out, float(v.z), order);
}

std::string oneLine(std::string text) {
    std::replace_if(
        text.begin(), text.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    return text;
}

void writeStl(std::ostream& out, const TriangleMesh& mesh, const MeshFileContent& content) {
    std::string header = "Lucent binary STL SPACE=LPS units=mm " + oneLine(content.description);
    header.resize(80, ' ');
    const std::vector<glm::dvec3> normals = triangleNormals(mesh);
    out.write(header.data(), 80);
    put(out, std::uint32_t(mesh.triangles.size()), std::endian::little);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        putVec(out, normals[t], std::endian::little);
        for (int k = 0; k < 3; ++k) {
            putVec(out, mesh.vertices[mesh.triangles[t][k]], std::endian::little);
        }
        put(out, std::uint16_t(0), std::endian::little);
    }
}

void writePly(std::ostream& out, const TriangleMesh& mesh, const MeshFileContent& content) {
    const bool svr = !content.svr.empty();
    out << "ply\nformat binary_little_endian 1.0\ncomment SPACE=LPS\ncomment units mm\n";
    if (!content.description.empty()) {
        out << "comment " << oneLine(content.description) << "\n";
    }
    if (svr) {
        out << "comment svr_radius_mm " << content.svrRadiusMm << "\ncomment svr colours viridis "
            << content.colourLo << " to " << content.colourHi << " per mm\n";
    }
    out << "element vertex " << mesh.vertices.size()
        << "\nproperty float x\nproperty float y\nproperty float z\n"
           "property float nx\nproperty float ny\nproperty float nz\n";
    if (svr) {
        out << "property uchar red\nproperty uchar green\nproperty uchar blue\n"
               "property float quality\nproperty float svr\n";
    }
    out << "element face " << mesh.triangles.size()
        << "\nproperty list uchar int vertex_indices\nend_header\n";
    const std::vector<glm::dvec3> normals = vertexNormals(mesh);
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        putVec(out, mesh.vertices[v], std::endian::little);
        putVec(out, normals[v], std::endian::little);
        if (svr) {
            for (const std::uint8_t c :
                 viridisBytes(content.svr[v], content.colourLo, content.colourHi)) {
                put(out, c, std::endian::little);
            }
            put(out, content.svr[v], std::endian::little);
            put(out, content.svr[v], std::endian::little);
        }
    }
    for (const glm::u32vec3& tri : mesh.triangles) {
        put(out, std::uint8_t(3), std::endian::little);
        for (int k = 0; k < 3; ++k) {
            put(out, std::int32_t(tri[k]), std::endian::little);
        }
    }
}

void writeVtk(std::ostream& out, const TriangleMesh& mesh, const MeshFileContent& content) {
    const auto big = std::endian::big;
    // Slicer reads the coordinate system from the title line.
    out << "# vtk DataFile Version 3.0\nLucent surface SPACE=LPS units=mm "
        << oneLine(content.description).substr(0, 200) << "\nBINARY\nDATASET POLYDATA\nPOINTS "
        << mesh.vertices.size() << " float\n";
    for (const glm::dvec3& v : mesh.vertices) {
        putVec(out, v, big);
    }
    out << "\nPOLYGONS " << mesh.triangles.size() << " " << 4 * mesh.triangles.size() << "\n";
    for (const glm::u32vec3& tri : mesh.triangles) {
        put(out, std::int32_t(3), big);
        for (int k = 0; k < 3; ++k) {
            put(out, std::int32_t(tri[k]), big);
        }
    }
    out << "\nPOINT_DATA " << mesh.vertices.size() << "\nNORMALS Normals float\n";
    for (const glm::dvec3& n : vertexNormals(mesh)) {
        putVec(out, n, big);
    }
    if (!content.svr.empty()) {
        out << "\nSCALARS svr float 1\nLOOKUP_TABLE default\n";
        for (const float s : content.svr) {
            put(out, s, big);
        }
    }
    out << "\n";
}

void writeObj(std::ostream& out, const TriangleMesh& mesh, const MeshFileContent& content) {
    out << "# SPACE=LPS\n# units mm\n";
    if (!content.description.empty()) {
        out << "# " << oneLine(content.description) << "\n";
    }
    const bool svr = !content.svr.empty();
    if (svr) {
        out << "# vertex colours: viridis of svr (1/mm, radius " << content.svrRadiusMm
            << " mm) over " << content.colourLo << " to " << content.colourHi << "\n";
    }
    char line[160];
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        const glm::dvec3& p = mesh.vertices[v];
        int n = std::snprintf(line, sizeof line, "v %.9g %.9g %.9g", p.x, p.y, p.z);
        if (svr) {
            const glm::dvec3 c = viridis((content.svr[v] - content.colourLo) /
                                         (content.colourHi - content.colourLo));
            n += std::snprintf(line + n, sizeof line - std::size_t(n), " %.4f %.4f %.4f", c.r, c.g,
                               c.b);
        }
        out.write(line, n) << '\n';
    }
    for (const glm::dvec3& nrm : vertexNormals(mesh)) {
        const int n = std::snprintf(line, sizeof line, "vn %.6f %.6f %.6f\n", nrm.x, nrm.y, nrm.z);
        out.write(line, n);
    }
    for (const glm::u32vec3& tri : mesh.triangles) {
        const int n = std::snprintf(line, sizeof line, "f %u//%u %u//%u %u//%u\n", tri.x + 1,
                                    tri.x + 1, tri.y + 1, tri.y + 1, tri.z + 1, tri.z + 1);
        out.write(line, n);
    }
}

} // namespace

MeshFileContent surfaceFileContent(const SurfaceResult& surface, double iso) {
    MeshFileContent content;
    char text[96];
    std::snprintf(text, sizeof text, "iso=%.1f", iso);
    content.description = text;
    if (surface.svr) {
        content.svr.assign(surface.svr->svr.begin(), surface.svr->svr.end());
        content.svrRadiusMm = surface.svr->radius;
        std::tie(content.colourLo, content.colourHi) = surfaceFieldRange(*surface.svr);
        std::snprintf(text, sizeof text, " svr_radius_mm=%.3f", surface.svr->radius);
        content.description += text;
    }
    return content;
}

MeshFormat meshFormatOf(const std::filesystem::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".stl") {
        return MeshFormat::Stl;
    }
    if (ext == ".ply") {
        return MeshFormat::Ply;
    }
    if (ext == ".vtk") {
        return MeshFormat::Vtk;
    }
    if (ext == ".obj") {
        return MeshFormat::Obj;
    }
    throw std::invalid_argument(
        file.string() + ": a mesh file ends in .stl, .ply, .vtk or .obj, not '" + ext + "'");
}

void writeMesh(const TriangleMesh& mesh, const std::filesystem::path& file, MeshFormat format,
               const MeshFileContent& content) {
    if (mesh.empty()) {
        throw std::invalid_argument(file.string() + ": the mesh has no triangles");
    }
    if (!content.svr.empty() && content.svr.size() != mesh.vertices.size()) {
        throw std::invalid_argument(file.string() + ": " + std::to_string(content.svr.size()) +
                                    " svr values for " + std::to_string(mesh.vertices.size()) +
                                    " vertices");
    }
    formats::AtomicFileWriter writer(file);
    std::ostream& out = writer.stream();
    switch (format) {
    case MeshFormat::Stl:
        writeStl(out, mesh, content);
        break;
    case MeshFormat::Ply:
        writePly(out, mesh, content);
        break;
    case MeshFormat::Vtk:
        writeVtk(out, mesh, content);
        break;
    case MeshFormat::Obj:
        writeObj(out, mesh, content);
        break;
    }
    writer.commit();
}

} // namespace lucent
