#include "core/surface/IsosurfaceExtractor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <sstream>
#include <tuple>
#include <type_traits>
#include <utility>

#include <omp.h>

#include "core/surface/FlyingEdges.h"
#include "core/surface/GaussianBlur.h"

namespace lucent {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The smallest and largest voxel value (NaN ignored), in parallel and
// vectorised: Volume::valueRange() is serial and cost as much as a pass of the
// extraction.
std::pair<double, double> valueRange(const Volume& volume) {
    return visitVoxels(volume, [](auto voxels) {
        using T = std::remove_const_t<typename decltype(voxels)::element_type>;
        T lo = std::numeric_limits<T>::max();
        T hi = std::numeric_limits<T>::lowest();
        const T* v = voxels.data();
        const auto n = static_cast<std::ptrdiff_t>(voxels.size());
#pragma omp parallel for schedule(static) reduction(min : lo) reduction(max : hi)
        for (std::ptrdiff_t i = 0; i < n; ++i) {
            lo = v[i] < lo ? v[i] : lo;
            hi = v[i] > hi ? v[i] : hi;
        }
        return std::pair{double(lo), double(hi)};
    });
}

void validate(const Volume& volume, const IsosurfaceOptions& options) {
    if (volume.empty()) {
        throw std::invalid_argument("isosurface: the volume is empty");
    }
    if (!std::isfinite(options.iso)) {
        throw std::invalid_argument("isosurface: the iso value is not a finite number");
    }
    if (!(options.smoothingSigma >= 0.0) || !std::isfinite(options.smoothingSigma)) {
        std::ostringstream s;
        s << "isosurface: smoothing sigma " << options.smoothingSigma
          << " must be a finite number of voxels >= 0";
        throw std::invalid_argument(s.str());
    }
    const auto [lo, hi] = valueRange(volume);
    if (options.iso < lo || options.iso > hi) {
        std::ostringstream s;
        s << "isosurface: iso value " << options.iso << " lies outside the volume's value range ["
          << lo << ", " << hi << "]";
        throw std::invalid_argument(s.str());
    }
}

// The voxels whose indices lie in the clip box, inclusive; first > last on
// some axis when there are none.
std::pair<glm::ivec3, glm::ivec3> clippedRange(const glm::ivec3& dims, const ClipBox& clip) {
    glm::ivec3 first, last;
    for (int a = 0; a < 3; ++a) {
        const double lo = std::ceil(clip.lo[a]);
        const double hi = std::floor(clip.hi[a]);
        // Written so that a NaN bound leaves the axis unclipped.
        first[a] = lo > 0.0 ? static_cast<int>(std::min(lo, double(dims[a]))) : 0;
        last[a] = hi < dims[a] - 1.0 ? static_cast<int>(std::max(hi, -1.0)) : dims[a] - 1;
    }
    return {first, last};
}

// The two values of a block that holds exactly two distinct values.
template <class T> std::optional<std::pair<double, double>> twoValues(const VoxelBlock<T>& b) {
    const T a = *b.data;
    std::optional<T> other;
    for (int k = 0; k < b.size.z; ++k) {
        for (int j = 0; j < b.size.y; ++j) {
            const T* v = b.row(j, k);
            for (int i = 0; i < b.size.x; ++i) {
                if (v[i] == a || (other && v[i] == *other)) {
                    continue;
                }
                if constexpr (std::is_floating_point_v<T>) {
                    if (std::isnan(v[i])) {
                        return std::nullopt;
                    }
                }
                if (other) {
                    return std::nullopt; // a third value
                }
                other = v[i];
            }
        }
    }
    if (!other) {
        return std::nullopt;
    }
    return std::pair{double(std::min(a, *other)), double(std::max(a, *other))};
}

std::string binaryWarning(std::pair<double, double> values) {
    std::ostringstream s;
    s << "the contoured voxels hold only two values (" << values.first << " and " << values.second
      << "): the surface of a binary mask over-estimates area by about 9 %; smooth it first "
         "(smoothing sigma of about 1 voxel)";
    return s.str();
}

template <class T>
void contour(const VoxelBlock<T>& block, const ContourSettings& settings, TriangleMesh& mesh) {
    if (!contourBlock(block, settings, mesh)) {
        throw IsosurfaceCancelled();
    }
}

// One call's inputs and output, for the typed steps below.
struct Extraction {
    const Volume& volume;
    const IsosurfaceOptions& options;
    glm::ivec3 first; // the clipped voxel range, inclusive
    glm::ivec3 last;
    IsosurfaceResult& result;

    // The voxels lo .. hi (inclusive) of the volume.
    template <class T>
    VoxelBlock<T> block(std::span<const T> voxels, glm::ivec3 lo, glm::ivec3 hi) const {
        const glm::ivec3 dims = volume.dims();
        return {voxels.data() + volume.linearIndex(lo.x, lo.y, lo.z), hi - lo + 1, dims.x,
                std::ptrdiff_t(dims.x) * dims.y};
    }
    // Contouring settings for a block whose first voxel is volume voxel lo.
    ContourSettings settings(glm::ivec3 lo) const {
        const glm::dmat4 indexToPatient = volume.geometry().indexToPatient();
        ContourSettings s;
        s.iso = options.iso;
        s.blockToPatient = indexToPatient;
        s.blockToPatient[3] = indexToPatient * glm::dvec4(glm::dvec3(lo), 1.0);
        s.flipWinding = glm::determinant(glm::dmat3(indexToPatient)) < 0.0;
        s.progress = options.progress;
        return s;
    }
};

template <class T> void contourVoxels(std::span<const T> voxels, Extraction& x) {
    const VoxelBlock<T> block = x.block(voxels, x.first, x.last);
    if (const auto values = twoValues(block)) {
        x.result.warnings.push_back(binaryWarning(*values));
    }
    contour(block, x.settings(x.first), x.result.mesh);
}

// Smooths the clip box plus the kernel's reach (within the volume), so that
// voxels near the clip faces see their true neighbours, then contours the box.
template <class T> void contourSmoothed(std::span<const T> voxels, Extraction& x) {
    const glm::ivec3 reach(gaussianRadius(x.options.smoothingSigma));
    const glm::ivec3 lo = glm::max(x.first - reach, glm::ivec3(0));
    const glm::ivec3 hi = glm::min(x.last + reach, x.volume.dims() - 1);
    const Clock::time_point start = Clock::now();
    std::vector<float> smoothed;
    if (!gaussianBlur(x.block(voxels, lo, hi), x.options.smoothingSigma, smoothed,
                      x.options.progress, 0.0, 0.4)) {
        throw IsosurfaceCancelled();
    }
    x.result.smoothMs = msSince(start);
    const glm::ivec3 n = hi - lo + 1;
    const glm::ivec3 offset = x.first - lo;
    const std::ptrdiff_t strideY = n.x, strideZ = std::ptrdiff_t(n.x) * n.y;
    const VoxelBlock<float> block{smoothed.data() + offset.x + offset.y * strideY +
                                      offset.z * strideZ,
                                  x.last - x.first + 1, strideY, strideZ};
    ContourSettings settings = x.settings(x.first);
    settings.progressFrom = 0.4;
    contour(block, settings, x.result.mesh);
}

} // namespace

IsosurfaceResult extractIsosurface(const Volume& volume, const IsosurfaceOptions& options) {
    const Clock::time_point start = Clock::now();
    validate(volume, options);
    IsosurfaceResult result;
    result.threads = omp_get_max_threads();
    std::tie(result.first, result.last) = clippedRange(volume.dims(), options.clip);
    if (glm::any(glm::greaterThan(result.first, result.last))) {
        result.warnings.push_back("the clip box holds no voxel of the volume");
    } else {
        Extraction x{volume, options, result.first, result.last, result};
        visitVoxels(volume, [&x](auto voxels) {
            if (x.options.smoothingSigma > 0.0) {
                contourSmoothed(voxels, x);
            } else {
                contourVoxels(voxels, x);
            }
        });
    }
    result.extractMs = msSince(start);
    return result;
}

} // namespace lucent
