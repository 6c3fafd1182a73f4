#pragma once
// Clean-up of an extracted mesh before it is shown, measured or exported:
// dropping small components (specks give absurd surface-to-volume values),
// windowed-sinc smoothing (no shrinkage, unlike Laplacian smoothing) and
// decimation. Each step changes area and volume, so measure afterwards.

#include <cstddef>

#include "core/surface/MeshChecks.h"
#include "core/surface/TriangleMesh.h"

namespace lucent {

// Components are the parts connected by shared vertices. One is dropped when
// it has fewer than minTriangles triangles or encloses less than minVolume
// (by |signed volume|: a cavity is its own component, with a negative volume).
// Of the rest, keepLargest keeps those with the most triangles (ties: the one
// whose first triangle comes first); triangle count rather than volume, as it
// needs no closed part.
struct ComponentFilter {
    std::size_t minTriangles = 0; // drop components with fewer triangles
    std::size_t keepLargest = 0;  // then keep only this many of the largest (0: all)
    double minVolume = 0.0;       // and drop those enclosing less than this |volume| (mm³)
};

struct ComponentFilterReport {
    std::size_t componentsBefore = 0;
    std::size_t componentsKept = 0;
    std::size_t componentsDropped = 0;
    std::size_t trianglesDropped = 0;
};

// Keeps the triangles of the chosen components in their order and the vertices
// they use in theirs (unused vertices are removed).
ComponentFilterReport filterComponents(TriangleMesh& mesh, const ComponentFilter& filter);

// Windowed-sinc low-pass smoothing (Taubin, Zhang & Golub 1996), as VTK's
// vtkWindowedSincPolyDataFilter: a Chebyshev expansion of an ideal low-pass
// filter of the umbrella operator, Hamming window, and VTK's Newton offset
// that puts the filter at 1 at the pass band. Unlike VTK, the coefficients are
// then scaled to sum to 1 exactly, so a translated mesh smooths to the
// translated result (VTK needs NormalizeCoordinates for that). Vertices on
// boundary edges stay fixed; the connectivity is untouched, so a watertight
// mesh stays watertight.
struct WindowedSincOptions {
    int iterations = 20;   // Chebyshev order, >= 1 (VTK's NumberOfIterations)
    double passBand = 0.1; // in (0, 2); smaller smooths more (VTK's PassBand)
};

// 3D Slicer's "smoothing factor" s in [0, 1] (0.5 by default) is passBand =
// 10^(-4 s) with 20 iterations: 0 -> 1, 0.25 -> 0.1, 0.5 -> 0.01, 1 -> 1e-4.
double slicerPassBand(double smoothingFactor);

// Throws std::invalid_argument for iterations < 1 or a pass band outside (0, 2).
void smoothWindowedSinc(TriangleMesh& mesh, const WindowedSincOptions& options);

// Decimation by meshoptimizer's edge collapse (meshopt_simplify, default
// options), ordered by a quadric error. Vertices keep their original (double)
// positions; the triangles change. It stops at the target or when the next
// collapse would exceed maxRelativeError (a fraction of the mesh extent), so
// the reached fraction can stay above the target. meshoptimizer 0.18 tries to
// keep the topology but does not check every collapse: a sphere stays closed,
// while CT bone at 0.25 (S2010, 300 HU) came out with a few hundred
// non-manifold and flipped edges. Hence DecimationReport::after, measured on
// the result. Slicer's "decimation factor" d is targetFraction = 1 - d.
struct DecimationOptions {
    double targetFraction = 0.25;  // of the triangles to keep, in (0, 1]
    double maxRelativeError = 1.0; // 1: no bound beyond the target
};

struct DecimationReport {
    std::size_t trianglesBefore = 0;
    std::size_t trianglesAfter = 0;
    double relativeError = 0.0; // meshoptimizer's error, a fraction of the extent
    double errorMm = 0.0;       // the same in mm
    MeshReport after;           // checked after decimation: watertight is measured, not assumed
};

// Throws std::invalid_argument for a target outside (0, 1] or a negative error.
DecimationReport decimate(TriangleMesh& mesh, const DecimationOptions& options);

} // namespace lucent
