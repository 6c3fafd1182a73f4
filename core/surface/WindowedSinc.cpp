// Windowed-sinc smoothing, declared in MeshCleanup.h.
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/surface/MeshCleanup.h"
#include "core/surface/MeshTopology.h"

namespace lucent {

namespace {

// Coefficients c_i of f(k) = sum c_i T_i(1 - k/2), the Hamming-windowed
// Chebyshev series of the ideal low-pass filter with cut-off k_pb, its cut-off
// offset by sigma so that f(k_pb) = 1 (Newton's method on sigma, as VTK does,
// but with the derivative in sigma), then scaled so that f(0) = 1.
std::vector<double> sincCoefficients(int order, double passBand) {
    const double pi = std::numbers::pi;
    const double theta = std::acos(1.0 - 0.5 * passBand);
    std::vector<double> window(order + 1), c(order + 1);
    for (int i = 0; i <= order; ++i) {
        window[i] = 0.54 + 0.46 * std::cos(i * pi / (order + 1));
    }
    double sigma = 0.0;
    for (int step = 0; step < 100; ++step) {
        double f = 0.0, df = 0.0;
        for (int i = 0; i <= order; ++i) {
            const double a = i * (theta + sigma);
            c[i] = i == 0 ? window[0] * (theta + sigma) / pi
                          : 2.0 * window[i] * std::sin(a) / (i * pi);
            const double dc = i == 0 ? window[0] / pi : 2.0 * window[i] * std::cos(a) / pi;
            f += c[i] * std::cos(i * theta); // T_i(cos theta) = cos(i theta)
            df += dc * std::cos(i * theta);
        }
        if (order < 2 || std::abs(f - 1.0) < 1e-9 || df == 0.0) {
            break; // order 1 has no free offset (VTK: "will most likely shrink")
        }
        sigma -= (f - 1.0) / df;
    }
    double sum = 0.0;
    for (const double ci : c) {
        sum += ci;
    }
    for (double& ci : c) {
        ci /= sum;
    }
    return c;
}

// Neighbours of each vertex through the edges (compressed rows). Vertices on
// a boundary edge get none, which keeps them fixed.
struct Neighbours {
    std::vector<std::uint32_t> start; // vertex v's neighbours: [start[v], start[v + 1])
    std::vector<std::uint32_t> list;
};

Neighbours neighbours(const TriangleMesh& mesh) {
    const std::vector<HalfEdge> halfEdges = sortedHalfEdges(mesh);
    std::vector<glm::u32vec2> edges; // distinct, (low, high)
    std::vector<bool> fixed(mesh.vertices.size(), false);
    std::size_t b = 0;
    while (b < halfEdges.size()) {
        std::size_t e = b + 1;
        while (e < halfEdges.size() && halfEdges[e].edge() == halfEdges[b].edge()) {
            ++e;
        }
        const glm::u32vec2 edge(halfEdges[b].low(), halfEdges[b].high());
        edges.push_back(edge);
        if (e - b == 1) {
            fixed[edge.x] = fixed[edge.y] = true;
        }
        b = e;
    }
    Neighbours n;
    n.start.assign(mesh.vertices.size() + 1, 0);
    for (const glm::u32vec2& edge : edges) {
        for (const std::uint32_t v : {edge.x, edge.y}) {
            n.start[v + 1] += fixed[v] ? 0 : 1;
        }
    }
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
        n.start[v + 1] += n.start[v];
    }
    n.list.resize(n.start.back());
    std::vector<std::uint32_t> fill(n.start.begin(), n.start.end() - 1);
    for (const glm::u32vec2& edge : edges) {
        for (int end = 0; end < 2; ++end) {
            const std::uint32_t v = edge[end];
            if (!fixed[v]) {
                n.list[fill[v]++] = edge[1 - end];
            }
        }
    }
    return n;
}

// (x + mean of the neighbours of x) / 2: the operator I - K/2 of the filter.
glm::dvec3 halfUmbrella(const std::vector<glm::dvec3>& x, const Neighbours& n, std::size_t v) {
    const std::uint32_t b = n.start[v], e = n.start[v + 1];
    if (b == e) {
        return x[v];
    }
    glm::dvec3 sum(0.0);
    for (std::uint32_t i = b; i < e; ++i) {
        sum += x[n.list[i]];
    }
    return 0.5 * (x[v] + sum / double(e - b));
}

} // namespace

double slicerPassBand(double smoothingFactor) {
    return std::pow(10.0, -4.0 * smoothingFactor);
}

void smoothWindowedSinc(TriangleMesh& mesh, const WindowedSincOptions& options) {
    if (options.iterations < 1 || !(options.passBand > 0.0 && options.passBand < 2.0)) {
        std::ostringstream s;
        s << "windowed-sinc smoothing: " << options.iterations
          << " iterations (need >= 1), pass band " << options.passBand
          << " (need 0 < pass band < 2)";
        throw std::invalid_argument(s.str());
    }
    if (mesh.triangles.empty()) {
        return;
    }
    const std::vector<double> c = sincCoefficients(options.iterations, options.passBand);
    const Neighbours n = neighbours(mesh);
    const auto count = static_cast<std::ptrdiff_t>(mesh.vertices.size());
    // The Chebyshev recursion T_{i+1} = 2 M T_i - T_{i-1} with M = I - K/2,
    // summed into the result as it goes.
    std::vector<glm::dvec3> previous = mesh.vertices, current(mesh.vertices.size());
    std::vector<glm::dvec3>& result = mesh.vertices;
    // Vertices without neighbours (fixed, or used by no triangle) keep their
    // exact position rather than one rounded through the sum.
    const auto moves = [&n](std::ptrdiff_t v) { return n.start[v] != n.start[v + 1]; };
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t v = 0; v < count; ++v) {
        current[v] = halfUmbrella(previous, n, v);
        if (moves(v)) {
            result[v] = c[0] * previous[v] + c[1] * current[v];
        }
    }
    std::vector<glm::dvec3> next(mesh.vertices.size());
    for (int i = 2; i <= options.iterations; ++i) {
#pragma omp parallel for schedule(static)
        for (std::ptrdiff_t v = 0; v < count; ++v) {
            next[v] = 2.0 * halfUmbrella(current, n, v) - previous[v];
            if (moves(v)) {
                result[v] += c[i] * next[v];
            }
        }
        std::swap(previous, current);
        std::swap(current, next);
    }
}

} // namespace lucent
