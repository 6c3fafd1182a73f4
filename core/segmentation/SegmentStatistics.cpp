#include "core/segmentation/SegmentStatistics.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "core/surface/IsosurfaceExtractor.h"
#include "core/surface/MeshChecks.h"

namespace lucent {
namespace {

using Point = glm::ivec2;

long cross(const Point& o, const Point& a, const Point& b) {
    return static_cast<long>(a.x - o.x) * (b.y - o.y) - static_cast<long>(a.y - o.y) * (b.x - o.x);
}

// Andrew's monotone chain: the hull's vertices (collinear points left out).
std::vector<Point> hull2d(std::vector<Point> p) {
    std::sort(p.begin(), p.end(),
              [](const Point& a, const Point& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
    p.erase(std::unique(p.begin(), p.end()), p.end());
    if (p.size() < 3) {
        return p;
    }
    std::vector<Point> h(2 * p.size());
    std::size_t k = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) {
            --k;
        }
        h[k++] = p[i];
    }
    for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) {
            --k;
        }
        h[k++] = p[i];
    }
    h.resize(k - 1);
    return h;
}

// The surface area (cm^2) of the mask's closed surface, on its bounding box plus a margin.
double surfaceAreaCm2(const SegmentMask& mask, const VolumeGeometry& grid, const glm::ivec3& lo,
                      const glm::ivec3& hi) {
    VolumeGeometry box = grid;
    const glm::ivec3 first = glm::max(lo - 3, glm::ivec3(0));
    const glm::ivec3 last = glm::min(hi + 3, grid.dims - 1);
    box.dims = last - first + 1;
    box.origin = grid.toPatient(glm::dvec3(first));
    Volume binary(box, VoxelType::UInt16);
    const std::span<std::uint16_t> v = binary.voxels<std::uint16_t>();
    for (int k = 0; k < box.dims.z; ++k) {
        for (int j = 0; j < box.dims.y; ++j) {
            for (int i = 0; i < box.dims.x; ++i) {
                v[binary.linearIndex(i, j, k)] =
                    mask.at(first.x + i, first.y + j, first.z + k) ? 1 : 0;
            }
        }
    }
    IsosurfaceOptions options;
    options.iso = 0.5;
    options.smoothingSigma = 1.0;
    return meshArea(extractIsosurface(binary, options).mesh) / 100.0;
}

} // namespace

double largestDiameterMm(const SegmentMask& mask, const VolumeGeometry& grid) {
    const glm::ivec3 d = mask.dims();
    std::vector<glm::dvec3> candidates;
    for (int k = 0; k < d.z; ++k) {
        std::vector<Point> ends;
        for (int j = 0; j < d.y; ++j) {
            int first = -1, last = -1;
            for (int i = 0; i < d.x; ++i) {
                if (mask.at(i, j, k)) {
                    first = first < 0 ? i : first;
                    last = i;
                }
            }
            if (first >= 0) {
                ends.push_back({first, j});
                ends.push_back({last, j});
            }
        }
        for (const Point& p : hull2d(std::move(ends))) {
            candidates.push_back(grid.toPatient(glm::dvec3(p.x, p.y, k)));
        }
    }
    if (candidates.empty()) {
        return SegmentStatistics::kNone;
    }
    double best = 0.0;
    const long n = static_cast<long>(candidates.size());
#pragma omp parallel for schedule(dynamic, 64) reduction(max : best)
    for (long a = 0; a < n; ++a) {
        for (long b = a + 1; b < n; ++b) {
            const glm::dvec3 e = candidates[a] - candidates[b];
            best = std::max(best, glm::dot(e, e));
        }
    }
    return std::sqrt(best);
}

SegmentStatistics segmentStatistics(const SegmentMask& mask, const Volume& volume) {
    if (mask.dims() != volume.dims()) {
        throw std::invalid_argument("segmentStatistics: the mask is not on the volume's grid");
    }
    SegmentStatistics s;
    std::vector<double> values;
    glm::ivec3 lo = mask.dims(), hi(-1);
    mask.forEachSet([&](std::size_t i) {
        const glm::ivec3 v = mask.voxelOf(i);
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
        values.push_back(volume.value(v.x, v.y, v.z));
    });
    s.voxels = values.size();
    const VolumeGeometry& g = volume.geometry();
    s.volumeMl = static_cast<double>(s.voxels) * g.spacing.x * g.spacing.y * g.spacing.z / 1000.0;
    if (values.empty()) {
        return s;
    }
    double mean = 0.0, m2 = 0.0;
    for (std::size_t n = 0; n < values.size(); ++n) {
        const double delta = values[n] - mean;
        mean += delta / static_cast<double>(n + 1);
        m2 += delta * (values[n] - mean);
    }
    s.mean = mean;
    s.standardDeviation = std::sqrt(m2 / static_cast<double>(values.size()));
    const auto [mn, mx] = std::minmax_element(values.begin(), values.end());
    s.minimum = *mn;
    s.maximum = *mx;
    const auto mid = values.begin() + static_cast<long>((values.size() - 1) / 2);
    std::nth_element(values.begin(), mid, values.end());
    s.median = *mid;
    s.surfaceAreaCm2 = surfaceAreaCm2(mask, g, lo, hi);
    s.largestDiameterMm = largestDiameterMm(mask, g);
    return s;
}

} // namespace lucent
