#pragma once
// From a volume to the surface a user asked for, in one place for the command
// line (lucent-cli surface) and the workstation's Surface panel: the
// isosurface, the clean-up (small components, windowed-sinc smoothing,
// decimation), its checks, and the method of spheres on exactly that mesh.

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/surface/MeshChecks.h"
#include "core/surface/SurfaceToVolume.h"
#include "core/surface/TriangleMesh.h"
#include "core/volume/BrickGrid.h"
#include "core/volume/Volume.h"

namespace lucent {

struct SurfaceRequest {
    double iso = 300.0;              // HU for CT
    ClipBox clip;                    // voxel indices; outside counts as outside
    double maskSigma = 0.0;          // Gaussian pre-smoothing (voxels), for binary masks
    double minComponentVoxels = 0.0; // drop parts enclosing less than this many voxels' volume
    std::size_t keepLargest = 0;     // then keep the K largest parts (0: all)
    int smoothIterations = 0;        // windowed-sinc iterations (0: none)
    double smoothPassBand = 0.1;     // its pass band (smaller smooths more)
    double decimate = 0.0;           // the fraction of triangles to remove, [0, 1)
    double svrRadius = 0.0;          // mm; 0: no surface-to-volume field
};

struct SurfaceResult {
    TriangleMesh mesh;
    MeshReport report; // of the final mesh
    std::size_t componentsDropped = 0;
    std::optional<SvrField> svr;
    double extractMs = 0.0, cleanupMs = 0.0, svrMs = 0.0;
    std::vector<std::string> warnings;
};

// Thrown when the progress hook asked to stop.
class SurfaceCancelled : public std::runtime_error {
public:
    SurfaceCancelled() : std::runtime_error("surface computation cancelled") {}
};

// The range a field is coloured over (viridis): its 5th to 95th percentile,
// so that a few specks or cavities do not wash out the rest.
std::pair<double, double> surfaceFieldRange(const SvrField& field);

// progress(fraction done over all steps, what is being done) returns false to
// cancel (SurfaceCancelled). Throws std::invalid_argument for a request out of
// range or an iso value outside the volume's values (the message names both);
// std::runtime_error when nothing is left ("no surface at iso ...").
SurfaceResult makeSurface(const Volume& volume, const SurfaceRequest& request,
                          const std::function<bool(double, const char*)>& progress = {});

} // namespace lucent
