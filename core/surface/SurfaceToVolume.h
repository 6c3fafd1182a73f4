#pragma once
// The method of spheres: the local surface-to-volume ratio SVR(X) = S/V at the
// vertices X of a closed triangle mesh, with S the area of the surface and V
// the volume of the solid inside the ball B(X, R), both exact for the mesh
// (closed forms per triangle, SphereIntegrals.h). At small R the field maps
// mean curvature (3/(2R) + 9H/16), at large R the local thickness (2/t for a
// plate of thickness t). Units follow the mesh: mm, mm², mm³ and mm⁻¹.
//
// Evaluated at mesh vertices only: there the interior solid angle Ω_int comes
// from the one-ring, and the triangles around X are seen edge-on by
// construction. The mesh must be closed, manifold and wound CCW seen from
// outside (what the isosurface extractor makes).

#include <cstdint>
#include <functional>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/surface/TriangleMesh.h"

namespace lucent {

struct SvrOptions {
    // Called with the fraction of vertices done (0 .. 1) about every 1 % of
    // them, on the calling thread; returning false cancels, and the compute
    // call then throws SvrCancelled. An exception it throws is rethrown.
    std::function<bool(double fractionDone)> progress;
    int threads = 0; // 0: OpenMP's default
    // Grid cell edge in units of R. Measured on a sphere of skull-like density
    // (327 k triangles, h ≈ 1.1 mm): R is 15 % faster than R/2 at R = 5 mm (R/2
    // takes a third fewer candidates but visits four times the cells, most of
    // them empty) and level at 2 mm; R/2 wins by about 5 % only where R/h ≥ 15.
    double cellSizeOverRadius = 1.0;
};

// Thrown when SvrOptions::progress asked to stop; no partial field is returned.
class SvrCancelled : public std::runtime_error {
public:
    SvrCancelled() : std::runtime_error("surface-to-volume computation cancelled") {}
};

struct SvrField {
    double radius = 0.0;        // R of the balls (mm)
    std::vector<double> svr;    // S/V per evaluated vertex (mm⁻¹); NaN where no triangle uses it
    std::vector<double> area;   // S: surface area inside the ball (mm²)
    std::vector<double> volume; // V: volume of the solid inside the ball (mm³)

    double totalArea = 0.0;             // S of the whole mesh (mm²)
    double totalVolume = 0.0;           // V of the whole solid (mm³)
    double totalRatio = 0.0;            // totalArea / totalVolume: the SVR of a ball holding it all
    double longestEdge = 0.0;           // h_max (mm): sets the discretisation error
    double longestEdgeOverRadius = 0.0; // h_max / R: SVR is trustworthy when small

    std::size_t unusedVertices = 0;  // evaluated vertices no triangle uses (NaN values)
    double candidatesPerQuery = 0.0; // triangles taken from the grid per vertex (mean)
    double clippedPerQuery = 0.0;    // of which crossed the sphere: the full clip (mean)
    std::size_t indexBytes = 0;      // memory of the index (triangles, grid, rings, stamps)
    double indexMs = 0.0;            // preparing triangles, grid and rings
    double svrMs = 0.0;              // the whole call, index included
    int threads = 0;                 // OpenMP threads used
};

// SVR at every vertex; the arrays follow mesh.vertices. Throws
// std::invalid_argument for a radius that is not finite and > 0, an empty or
// open mesh, bad indices or non-finite coordinates; SvrCancelled on cancel.
SvrField computeSvrField(const TriangleMesh& mesh, double radius, const SvrOptions& options = {});

// The same at the listed vertices only; the arrays follow `vertices`.
SvrField computeSvrAt(const TriangleMesh& mesh, double radius,
                      std::span<const std::uint32_t> vertices, const SvrOptions& options = {});

} // namespace lucent
