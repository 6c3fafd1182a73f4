#include "core/surface/MeshCleanup.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <meshoptimizer.h>

#include "core/surface/MeshTopology.h"

namespace lucent {

namespace {

// Triangle count and signed enclosed volume of each component.
struct ComponentSizes {
    std::vector<std::size_t> triangles;
    std::vector<double> volume;
};

ComponentSizes measure(const TriangleMesh& mesh, const TriangleComponents& components) {
    ComponentSizes out{std::vector<std::size_t>(components.count, 0),
                       std::vector<double>(components.count, 0.0)};
    // About one point: any point gives a closed part the same volume.
    const glm::dvec3 o = mesh.vertices.empty() ? glm::dvec3(0.0) : mesh.vertices.front();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const glm::u32vec3& tri = mesh.triangles[t];
        const std::uint32_t label = components.label[t];
        ++out.triangles[label];
        const glm::dvec3 a = mesh.vertices[tri[0]] - o, b = mesh.vertices[tri[1]] - o;
        out.volume[label] += glm::dot(a, glm::cross(b, mesh.vertices[tri[2]] - o)) / 6.0;
    }
    return out;
}

} // namespace

ComponentFilterReport filterComponents(TriangleMesh& mesh, const ComponentFilter& filter) {
    const TriangleComponents components = triangleComponents(mesh);
    const ComponentSizes sizes = measure(mesh, components);
    const std::vector<std::size_t>& size = sizes.triangles;
    // Labels follow the first triangle, so a stable sort breaks ties by it.
    std::vector<std::uint32_t> order(components.count);
    std::iota(order.begin(), order.end(), std::uint32_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return size[a] > size[b]; });
    std::vector<bool> keep(components.count, false);
    ComponentFilterReport report;
    report.componentsBefore = components.count;
    for (const std::uint32_t label : order) {
        const bool largeEnough =
            size[label] >= filter.minTriangles && std::abs(sizes.volume[label]) >= filter.minVolume;
        const bool room = filter.keepLargest == 0 || report.componentsKept < filter.keepLargest;
        if (largeEnough && room) {
            keep[label] = true;
            ++report.componentsKept;
        } else {
            ++report.componentsDropped;
            report.trianglesDropped += size[label];
        }
    }
    std::size_t kept = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        if (keep[components.label[t]]) {
            mesh.triangles[kept++] = mesh.triangles[t];
        }
    }
    mesh.triangles.resize(kept);
    removeUnusedVertices(mesh);
    return report;
}

namespace {

void validate(const DecimationOptions& options) {
    if (!(options.targetFraction > 0.0 && options.targetFraction <= 1.0) ||
        !(options.maxRelativeError >= 0.0)) {
        std::ostringstream s;
        s << "decimation: target fraction " << options.targetFraction
          << " must lie in (0, 1] and the error bound " << options.maxRelativeError
          << " must be >= 0";
        throw std::invalid_argument(s.str());
    }
}

// Float positions about the box centre, so that float precision is spent on
// the shape rather than on the distance to the patient origin.
std::vector<float> floatPositions(const TriangleMesh& mesh) {
    glm::dvec3 lo(0.0), hi(0.0);
    if (!mesh.vertices.empty()) {
        lo = hi = mesh.vertices.front();
    }
    for (const glm::dvec3& v : mesh.vertices) {
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    const glm::dvec3 centre = 0.5 * (lo + hi);
    std::vector<float> positions;
    positions.reserve(3 * mesh.vertices.size());
    for (const glm::dvec3& v : mesh.vertices) {
        for (int a = 0; a < 3; ++a) {
            positions.push_back(static_cast<float>(v[a] - centre[a]));
        }
    }
    return positions;
}

} // namespace

DecimationReport decimate(TriangleMesh& mesh, const DecimationOptions& options) {
    validate(options);
    DecimationReport report;
    report.trianglesBefore = mesh.triangles.size();
    if (!mesh.triangles.empty() && options.targetFraction < 1.0) {
        const std::vector<float> positions = floatPositions(mesh);
        std::vector<unsigned int> indices;
        indices.reserve(3 * mesh.triangles.size());
        for (const glm::u32vec3& t : mesh.triangles) {
            indices.insert(indices.end(), {t[0], t[1], t[2]});
        }
        const auto target = static_cast<std::size_t>(
            3.0 * std::round(options.targetFraction * static_cast<double>(mesh.triangles.size())));
        std::vector<unsigned int> kept(indices.size());
        float error = 0.0f;
        kept.resize(meshopt_simplify(kept.data(), indices.data(), indices.size(), positions.data(),
                                     mesh.vertices.size(), 3 * sizeof(float), target,
                                     static_cast<float>(options.maxRelativeError), 0, &error));
        mesh.triangles.resize(kept.size() / 3);
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
            mesh.triangles[t] = {kept[3 * t], kept[3 * t + 1], kept[3 * t + 2]};
        }
        report.relativeError = error;
        report.errorMm = error * meshopt_simplifyScale(positions.data(), mesh.vertices.size(),
                                                       3 * sizeof(float));
        removeUnusedVertices(mesh);
    }
    report.trianglesAfter = mesh.triangles.size();
    report.after = checkMesh(mesh);
    return report;
}

} // namespace lucent
