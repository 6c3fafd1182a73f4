#include "core/raycast/SurfaceDepth.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "core/raycast/RaySetup.h"
#include "core/raycast/VolumeFields.h"
#include "core/scene/ImageProjection.h"
#include "core/scene/ViewFrame.h"

namespace lucent {
namespace {

// One ray, index space: origin o, direction d per mm of patient distance.
struct IndexRay {
    glm::dvec3 o{0.0}, d{0.0};
    RaySpan span;
    double dt = 1.0;
    glm::dvec3 at(double t) const { return o + d * t; }
    double sampleT(long n) const { return span.t0 + double(n) * dt; }
};

template <class Field>
std::optional<glm::dvec3> march(const RenderDescription& desc, const Field& field,
                                const IndexRay& ray) {
    const TransferFunction& tf = desc.transferFunction;
    const double step = desc.sampling.step;
    switch (desc.mode) {
    case RenderMode::Dvr: {
        const double threshold = std::min(kSurfaceOpacity, desc.sampling.earlyTermination);
        double accumulated = 0.0;
        for (long n = ray.span.nFirst; n <= ray.span.nLast; ++n) {
            const glm::dvec3 p = ray.at(ray.sampleT(n));
            const double a = std::min(tf.opacityAt(double(field.value(p))), 1.0);
            if (a <= 0.0) {
                continue;
            }
            accumulated += (1.0 - accumulated) * (1.0 - std::pow(1.0 - a, step));
            if (accumulated >= threshold) {
                return p;
            }
        }
        return std::nullopt;
    }
    case RenderMode::Isosurface: {
        const double iso = desc.isoValue;
        bool havePrevious = false;
        double previous = 0.0, tPrevious = 0.0;
        for (long n = ray.span.nFirst; n <= ray.span.nLast; ++n) {
            const double t = ray.sampleT(n);
            const double v = double(field.value(ray.at(t)));
            if (havePrevious && (previous < iso) != (v < iso)) {
                double a = tPrevious, b = t, va = previous;
                for (int it = 0; it < 40 && b - a > 1e-9 * ray.dt; ++it) {
                    const double m = 0.5 * (a + b);
                    const double vm = double(field.value(ray.at(m)));
                    if ((va < iso) == (vm < iso)) {
                        a = m;
                        va = vm;
                    } else {
                        b = m;
                    }
                }
                return ray.at(0.5 * (a + b));
            }
            previous = v;
            tPrevious = t;
            havePrevious = true;
        }
        return std::nullopt;
    }
    case RenderMode::Mip:
    case RenderMode::MinIp: {
        const bool max = desc.mode == RenderMode::Mip;
        std::optional<glm::dvec3> where;
        double extreme = 0.0;
        for (long n = ray.span.nFirst; n <= ray.span.nLast; ++n) {
            const glm::dvec3 p = ray.at(ray.sampleT(n));
            const double v = double(field.value(p));
            if (!where || (max ? v > extreme : v < extreme)) {
                extreme = v;
                where = p;
            }
        }
        if (where && tf.opacityAt(extreme) >= kSurfaceOpacity) {
            return where;
        }
        return std::nullopt;
    }
    case RenderMode::Average:
        break;
    }
    return std::nullopt;
}

} // namespace

std::optional<glm::dvec3> surfacePoint(const RenderDescription& desc, glm::dvec2 fraction) {
    if (desc.volume == nullptr) {
        throw std::invalid_argument("surfacePoint: the description has no volume");
    }
    const Volume& volume = *desc.volume;
    const VolumeGeometry& g = volume.geometry();
    const ViewFrame frame = makeViewFrame(g, desc.camera, desc.width, desc.height);
    const glm::dvec3 w = rayThroughFraction(frame, fraction, desc.width, desc.height);
    const glm::dmat3 toIndexLinear = glm::inverse(glm::dmat3(
        g.direction[0] * g.spacing.x, g.direction[1] * g.spacing.y, g.direction[2] * g.spacing.z));
    IndexRay ray;
    ray.o = g.toIndex(frame.eye);
    ray.d = toIndexLinear * w;
    ray.dt = desc.sampling.step * std::min({g.spacing.x, g.spacing.y, g.spacing.z});
    const glm::dvec3 boxLo(0.0), boxHi(g.dims - 1);
    if (!raySpanIn(boxLo, boxHi, glm::max(desc.clip.lo, boxLo), glm::min(desc.clip.hi, boxHi),
                   glm::bvec3(false), ray.dt, ray.o, ray.d, ray.span)) {
        return std::nullopt;
    }
    const std::optional<glm::dvec3> index = visitVoxels(volume, [&](auto voxels) {
        using T = std::remove_const_t<typename decltype(voxels)::element_type>;
        const LinearField<double, T> field{Grid<double, T>(voxels.data(), g.dims)};
        return march(desc, field, ray);
    });
    if (!index) {
        return std::nullopt;
    }
    return g.toPatient(*index);
}

std::vector<glm::dvec3> surfaceAnchors(const RenderDescription& desc,
                                       const std::vector<glm::dvec2>& fractions) {
    if (desc.volume == nullptr) {
        throw std::invalid_argument("surfaceAnchors: the description has no volume");
    }
    const VolumeGeometry& g = desc.volume->geometry();
    const ViewFrame frame = makeViewFrame(g, desc.camera, desc.width, desc.height);
    std::vector<std::optional<glm::dvec3>> found;
    found.reserve(fractions.size());
    std::optional<double> depth; // along the view's forward axis
    for (const glm::dvec2& f : fractions) {
        found.push_back(surfacePoint(desc, f));
        if (found.back() && !depth) {
            depth = glm::dot(*found.back() - frame.eye, frame.forward);
        }
    }
    const glm::dvec3 target =
        volumeCentre(g) + frame.right * desc.camera.panRight + frame.up * desc.camera.panUp;
    const double planeDepth = depth.value_or(glm::dot(target - frame.eye, frame.forward));
    std::vector<glm::dvec3> anchors;
    anchors.reserve(fractions.size());
    for (std::size_t n = 0; n < fractions.size(); ++n) {
        if (found[n]) {
            anchors.push_back(*found[n]);
            continue;
        }
        const glm::dvec3 w = rayThroughFraction(frame, fractions[n], desc.width, desc.height);
        anchors.push_back(frame.eye + w * (planeDepth / glm::dot(w, frame.forward)));
    }
    return anchors;
}

} // namespace lucent
