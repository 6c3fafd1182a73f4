#include "core/quality/SceneCost.h"

#include "core/raycast/RaySetup.h"
#include "core/scene/ViewFrame.h"

namespace lucent {

std::size_t bruteForceSamples(const RenderDescription& desc) {
    const VolumeGeometry& g = desc.volume->geometry();
    // The ray setup of the ray casters (CpuRayCaster::render, castImage).
    RaySetup<double> s;
    s.dt = desc.sampling.step * std::min({g.spacing.x, g.spacing.y, g.spacing.z});
    s.boxLo = glm::dvec3(0.0);
    s.boxHi = glm::dvec3(g.dims - 1);
    s.clipLo = glm::max(desc.clip.lo, s.boxLo);
    s.clipHi = glm::min(desc.clip.hi, s.boxHi);
    const glm::dmat3 toIndex = glm::inverse(glm::dmat3(
        g.direction[0] * g.spacing.x, g.direction[1] * g.spacing.y, g.direction[2] * g.spacing.z));
    const ViewFrame frame = makeViewFrame(g, desc.camera, desc.width, desc.height);
    const glm::dvec3 origin = g.toIndex(frame.eye);
    std::size_t total = 0;
#pragma omp parallel for reduction(+ : total) schedule(static)
    for (int y = 0; y < desc.height; ++y) {
        for (int x = 0; x < desc.width; ++x) {
            const glm::dvec3 d = toIndex * frame.rayDirection(x, y, desc.width, desc.height);
            RaySpan span;
            if (raySpan(s, origin, d, span) && span.nLast >= span.nFirst) {
                total += std::size_t(span.nLast - span.nFirst + 1);
            }
        }
    }
    return total;
}

} // namespace lucent
