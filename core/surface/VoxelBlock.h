#pragma once
// Internal to the isosurface extractor: a box of voxels inside a larger array
// (the clip box of a volume, or a smoothed copy of it), and the chunked
// parallel loop that reports progress between chunks.

#include <algorithm>
#include <cstddef>
#include <functional>

#include <glm/glm.hpp>

namespace lucent {

// Voxel (i, j, k) of the box, 0 <= i < size.x ..., is
// data[i + j * strideY + k * strideZ].
template <class T> struct VoxelBlock {
    const T* data = nullptr;
    glm::ivec3 size{0};
    std::ptrdiff_t strideY = 0;
    std::ptrdiff_t strideZ = 0;

    const T* row(int j, int k) const { return data + j * strideY + k * strideZ; }
};

// Runs work(s) for every s in [0, count) with OpenMP, in up to 16 chunks when
// a progress hook is set. After each chunk the hook gets the fraction done,
// mapped onto [from, to], on the calling thread (never from a worker thread).
// Returns false when the hook asked to stop. work must not throw.
template <class Work>
bool parallelChunks(int count, double from, double to, const std::function<bool(double)>& progress,
                    const Work& work) {
    const int chunks = progress ? std::clamp(count, 1, 16) : 1;
    for (int chunk = 0; chunk < chunks; ++chunk) {
        const int begin = static_cast<int>(static_cast<long long>(count) * chunk / chunks);
        const int end = static_cast<int>(static_cast<long long>(count) * (chunk + 1) / chunks);
#pragma omp parallel for schedule(dynamic, 1)
        for (int s = begin; s < end; ++s) {
            work(s);
        }
        if (progress && !progress(from + (to - from) * (chunk + 1) / chunks)) {
            return false;
        }
    }
    return true;
}

} // namespace lucent
