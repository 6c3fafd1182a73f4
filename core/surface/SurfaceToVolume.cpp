#include "core/surface/SurfaceToVolume.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include <omp.h>

#include "core/surface/SphereIntegrals.h"
#include "core/surface/TriangleGrid.h"
#include "core/surface/VertexRings.h"

namespace lucent {

namespace {

constexpr std::size_t kChunk = 32;              // vertices per scheduling unit
constexpr std::size_t kMaxCellsPerTriangle = 8; // caps the grid's offset array
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void validate(const TriangleMesh& mesh, double radius, std::span<const std::uint32_t> vertices,
              const SvrOptions& options) {
    if (!std::isfinite(radius) || radius <= 0.0) {
        std::ostringstream message;
        message << "SVR radius must be finite and > 0, got " << radius;
        throw std::invalid_argument(message.str());
    }
    if (!std::isfinite(options.cellSizeOverRadius) || options.cellSizeOverRadius <= 0.0) {
        throw std::invalid_argument("SVR grid cell size over radius must be finite and > 0");
    }
    if (mesh.triangles.empty() || mesh.vertices.empty()) {
        throw std::invalid_argument("SVR needs a closed triangle mesh, got an empty one (" +
                                    std::to_string(mesh.vertices.size()) + " vertices, " +
                                    std::to_string(mesh.triangles.size()) + " triangles)");
    }
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        const glm::dvec3& p = mesh.vertices[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            throw std::invalid_argument("vertex " + std::to_string(i) +
                                        " has a non-finite coordinate");
        }
    }
    for (const std::uint32_t v : vertices) {
        if (v >= mesh.vertices.size()) {
            throw std::invalid_argument("SVR asked at vertex " + std::to_string(v) +
                                        " of a mesh with " + std::to_string(mesh.vertices.size()) +
                                        " vertices");
        }
    }
}

// Triangles prepared and sorted by the Z-order of their centroid's cell, so
// that the triangles of neighbouring cells sit near each other in memory.
std::vector<PreparedTriangle> prepareTriangles(const TriangleMesh& mesh, const GridFrame& frame,
                                               int threads) {
    const std::size_t n = mesh.triangles.size();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> order(n);
    for (std::uint32_t i = 0; i < n; ++i) {
        const glm::u32vec3& t = mesh.triangles[i];
        const glm::dvec3 centroid =
            (mesh.vertices[t.x] + mesh.vertices[t.y] + mesh.vertices[t.z]) / 3.0;
        order[i] = {frame.mortonKey(centroid), i};
    }
    std::sort(order.begin(), order.end());
    std::vector<PreparedTriangle> prepared(n);
#pragma omp parallel for schedule(static) num_threads(threads)
    for (std::int64_t i = 0; i < std::int64_t(n); ++i) {
        const glm::u32vec3& t = mesh.triangles[order[std::size_t(i)].second];
        prepared[std::size_t(i)] =
            prepareTriangle(mesh.vertices[t.x], mesh.vertices[t.y], mesh.vertices[t.z]);
    }
    return prepared;
}

// Whole-mesh figures: area, volume (about the first vertex, so that far-off
// coordinates lose no digits) and the longest edge.
void measureMesh(const TriangleMesh& mesh, SvrField& field) {
    const glm::dvec3 centre = mesh.vertices.front();
    double area = 0.0, volume6 = 0.0, longest2 = 0.0;
    for (const glm::u32vec3& t : mesh.triangles) {
        const glm::dvec3 a = mesh.vertices[t.x] - centre, b = mesh.vertices[t.y] - centre,
                         c = mesh.vertices[t.z] - centre;
        area += 0.5 * glm::length(glm::cross(b - a, c - a));
        volume6 += glm::dot(a, glm::cross(b, c));
        longest2 = std::max(
            {longest2, glm::dot(b - a, b - a), glm::dot(c - b, c - b), glm::dot(a - c, a - c)});
    }
    field.totalArea = area;
    field.totalVolume = volume6 / 6.0;
    field.totalRatio = area / field.totalVolume;
    field.longestEdge = std::sqrt(longest2);
    field.longestEdgeOverRadius = field.longestEdge / field.radius;
}

// Ω_int at each listed vertex (NaN where no triangle uses it); throws when a
// used vertex has an open or non-manifold fan.
std::vector<double> interiorSolidAngles(const VertexRings& rings,
                                        std::span<const std::uint32_t> vertices, int threads) {
    std::vector<double> omega(vertices.size(), kNaN);
    std::size_t open = 0;
    std::uint32_t firstOpen = std::numeric_limits<std::uint32_t>::max();
#pragma omp parallel num_threads(threads) reduction(+ : open) reduction(min : firstOpen)
    {
        std::vector<std::uint32_t> scratch;
#pragma omp for schedule(static)
        for (std::int64_t i = 0; i < std::int64_t(vertices.size()); ++i) {
            const std::uint32_t v = vertices[std::size_t(i)];
            if (rings.trianglesAt(v).empty()) {
                continue;
            }
            const std::optional<double> angle = rings.interiorSolidAngle(v, scratch);
            if (angle) {
                omega[std::size_t(i)] = *angle;
            } else {
                ++open, firstOpen = std::min(firstOpen, v);
            }
        }
    }
    if (open > 0) {
        throw std::invalid_argument(
            "mesh is not closed: the triangles around vertex " + std::to_string(firstOpen) +
            " do not form closed fans (" + std::to_string(open) +
            " such vertices); SVR needs a closed, manifold, consistently wound surface");
    }
    return omega;
}

// Slots of `vertices` in the Z-order of their grid cells, for cache locality.
std::vector<std::uint32_t> queryOrder(const TriangleMesh& mesh, const GridFrame& frame,
                                      std::span<const std::uint32_t> vertices) {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(vertices.size());
    for (std::uint32_t i = 0; i < vertices.size(); ++i) {
        keyed[i] = {frame.mortonKey(mesh.vertices[vertices[i]]), i};
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<std::uint32_t> order(keyed.size());
    std::transform(keyed.begin(), keyed.end(), order.begin(), [](auto& k) { return k.second; });
    return order;
}

// Calls the progress hook from thread 0 about every 1 % of the queries; turns
// a "stop" answer or an exception of the hook into a cancel of the loop.
class ProgressGate {
public:
    ProgressGate(const SvrOptions& options, std::size_t total)
        : hook_(options.progress), total_(total), step_(std::max<std::size_t>(1, total / 100)),
          next_(step_) {}

    bool stopped() const { return stop_.load(std::memory_order_relaxed); }

    void finished(std::size_t count) {
        const std::size_t done = done_.fetch_add(count, std::memory_order_relaxed) + count;
        if (!hook_ || omp_get_thread_num() != 0 || done < next_ || done >= total_) {
            return;
        }
        next_ = done + step_;
        try {
            if (!hook_(double(done) / double(total_))) {
                stop_ = true;
            }
        } catch (...) {
            error_ = std::current_exception();
            stop_ = true;
        }
    }

    // After the loop: rethrows the hook's exception or reports the cancel.
    void throwIfStopped() const {
        if (error_) {
            std::rethrow_exception(error_);
        }
        if (stopped()) {
            throw SvrCancelled();
        }
    }

private:
    const std::function<bool(double)>& hook_;
    std::size_t total_, step_, next_; // next_: touched by thread 0 only
    std::atomic<std::size_t> done_{0};
    std::atomic<bool> stop_{false};
    std::exception_ptr error_; // written by thread 0 only
};

struct QueryTally {
    std::uint64_t queries = 0, candidates = 0, clipped = 0;

    void add(const QueryTally& other) {
        queries += other.queries, candidates += other.candidates, clipped += other.clipped;
    }
};

// S and V of the ball at one vertex.
std::pair<double, double> sphereSums(const TriangleGrid& grid,
                                     std::span<const PreparedTriangle> triangles, const Ball& ball,
                                     double omegaInt, QueryStamps& stamps, QueryTally& tally) {
    BallSums sums(ball);
    std::uint64_t candidates = 0, clipped = 0;
    grid.forEachCandidate(ball.centre, ball.radius, stamps, [&](std::uint32_t id) {
        clipped += sums.add(triangles[id]) == BallPath::Clipped ? 1 : 0;
        ++candidates;
    });
    tally.queries += 1, tally.candidates += candidates, tally.clipped += clipped;
    return {sums.area(), sums.volume(omegaInt)};
}

// Everything the queries read, built once per call.
struct SvrIndex {
    SvrIndex(const TriangleMesh& mesh, const GridFrame& gridFrame,
             std::span<const std::uint32_t> vertices, int threads)
        : rings(mesh), omegaInt(interiorSolidAngles(rings, vertices, threads)), frame(gridFrame),
          triangles(prepareTriangles(mesh, frame, threads)), grid(frame, triangles),
          order(queryOrder(mesh, frame, vertices)) {}

    std::size_t memoryBytes(int threads) const {
        const std::size_t stamps = sizeof(std::uint32_t) * triangles.size() * std::size_t(threads);
        return rings.memoryBytes() + grid.memoryBytes() + stamps +
               triangles.size() * sizeof(PreparedTriangle) +
               omegaInt.size() * (sizeof(double) + sizeof(std::uint32_t));
    }

    const VertexRings rings; // built first: it checks the indices everything else reads through
    const std::vector<double> omegaInt; // Ω_int per evaluated vertex; NaN where unused
    const GridFrame frame;
    const std::vector<PreparedTriangle> triangles; // in Z-order, as the grid numbers them
    const TriangleGrid grid;
    const std::vector<std::uint32_t> order; // evaluation order of the vertex slots
};

GridFrame gridFrameFor(const TriangleMesh& mesh, double radius, const SvrOptions& options) {
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const glm::dvec3& p : mesh.vertices) {
        lo = glm::min(lo, p), hi = glm::max(hi, p);
    }
    return GridFrame(lo, hi, radius * options.cellSizeOverRadius,
                     kMaxCellsPerTriangle * mesh.triangles.size());
}

// S, V and S/V at each vertex slot, in chunks over the threads.
QueryTally evaluate(const TriangleMesh& mesh, std::span<const std::uint32_t> vertices,
                    const SvrIndex& index, double radius, const SvrOptions& options, int threads,
                    SvrField& field) {
    const std::size_t count = vertices.size();
    field.svr.assign(count, kNaN), field.area.assign(count, kNaN), field.volume.assign(count, kNaN);
    ProgressGate gate(options, count);
    QueryTally total;
    const std::int64_t chunks = std::int64_t((count + kChunk - 1) / kChunk);
#pragma omp parallel num_threads(threads)
    {
        QueryStamps stamps(index.triangles.size());
        QueryTally tally;
#pragma omp for schedule(dynamic, 1) nowait
        for (std::int64_t chunk = 0; chunk < chunks; ++chunk) {
            if (gate.stopped()) {
                continue;
            }
            const std::size_t begin = std::size_t(chunk) * kChunk;
            const std::size_t end = std::min(begin + kChunk, count);
            for (std::size_t i = begin; i < end; ++i) {
                const std::uint32_t slot = index.order[i];
                if (std::isnan(index.omegaInt[slot])) {
                    continue;
                }
                const Ball ball(mesh.vertices[vertices[slot]], radius);
                const auto [s, v] = sphereSums(index.grid, index.triangles, ball,
                                               index.omegaInt[slot], stamps, tally);
                field.area[slot] = s, field.volume[slot] = v, field.svr[slot] = s / v;
            }
            gate.finished(end - begin);
        }
#pragma omp critical(lucent_svr_tally)
        total.add(tally);
    }
    gate.throwIfStopped();
    return total;
}

} // namespace

SvrField computeSvrAt(const TriangleMesh& mesh, double radius,
                      std::span<const std::uint32_t> vertices, const SvrOptions& options) {
    const Clock::time_point start = Clock::now();
    validate(mesh, radius, vertices, options);
    SvrField field;
    field.radius = radius;
    field.threads = options.threads > 0 ? options.threads : omp_get_max_threads();
    const SvrIndex index(mesh, gridFrameFor(mesh, radius, options), vertices, field.threads);
    measureMesh(mesh, field);
    field.indexBytes = index.memoryBytes(field.threads);
    field.indexMs = msSince(start);

    const QueryTally tally = evaluate(mesh, vertices, index, radius, options, field.threads, field);
    field.unusedVertices = vertices.size() - tally.queries;
    const double queries = double(std::max<std::uint64_t>(1, tally.queries));
    field.candidatesPerQuery = double(tally.candidates) / queries;
    field.clippedPerQuery = double(tally.clipped) / queries;
    field.svrMs = msSince(start);
    return field;
}

SvrField computeSvrField(const TriangleMesh& mesh, double radius, const SvrOptions& options) {
    std::vector<std::uint32_t> all(mesh.vertices.size());
    std::iota(all.begin(), all.end(), 0u);
    return computeSvrAt(mesh, radius, all, options);
}

} // namespace lucent
