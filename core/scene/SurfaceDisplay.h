#pragma once
// A surface shown with the volume (GL-free; the GPU ray caster draws it):
// the mesh lit, coloured by a per-vertex field (viridis over [lo, hi],
// core/image/ColourMap.h) or plain, and the volume's rays stopped at it so
// that each occludes the other correctly. Shared by the 3D view, its controls
// and the renderer; never changed once made (a new display replaces it).

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "core/surface/TriangleMesh.h"

namespace lucent {

struct SurfaceDisplay {
    std::shared_ptr<const TriangleMesh> mesh; // LPS mm
    // Per vertex (the SVR field, 1/mm), or empty: the plain colour.
    std::shared_ptr<const std::vector<float>> field;
    double fieldLo = 0.0, fieldHi = 1.0;
    glm::dvec3 colour{0.89, 0.85, 0.78}; // plain: bone white
    bool showVolume = true;              // false: the surface alone over the background
};

} // namespace lucent
