#include "core/surface/GaussianBlur.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lucent {

namespace {

std::vector<float> gaussianWeights(double sigma) {
    const int radius = gaussianRadius(sigma);
    std::vector<double> w(2 * radius + 1);
    double sum = 0.0;
    for (int d = -radius; d <= radius; ++d) {
        w[d + radius] = std::exp(-0.5 * d * d / (sigma * sigma));
        sum += w[d + radius];
    }
    std::vector<float> weights(w.size());
    for (std::size_t i = 0; i < w.size(); ++i) {
        weights[i] = static_cast<float>(w[i] / sum);
    }
    return weights;
}

// out[0 .. length) = sum over d of w[d + r] * line (at + d), lines `stride`
// apart in `in`, the index clamped to [0, count): one output line of a pass
// along y (lines are rows) or z (lines are slices).
void blurLine(float* out, const float* in, std::size_t length, std::size_t stride, int at,
              int count, const std::vector<float>& w) {
    const int r = static_cast<int>(w.size() / 2);
    std::fill(out, out + length, 0.0f);
    for (int d = -r; d <= r; ++d) {
        const float* line = in + std::clamp(at + d, 0, count - 1) * stride;
        const float weight = w[d + r];
        for (std::size_t i = 0; i < length; ++i) {
            out[i] += weight * line[i];
        }
    }
}

// One row along x, from the voxels.
template <class T> void blurRow(float* out, const T* v, int n, const std::vector<float>& w) {
    const int r = static_cast<int>(w.size() / 2);
    for (int i = 0; i < n; ++i) {
        float sum = 0.0f;
        for (int d = -r; d <= r; ++d) {
            sum += w[d + r] * static_cast<float>(v[std::clamp(i + d, 0, n - 1)]);
        }
        out[i] = sum;
    }
}

} // namespace

int gaussianRadius(double sigma) {
    return std::max(1, static_cast<int>(std::ceil(3.0 * sigma)));
}

template <class T>
bool gaussianBlur(const VoxelBlock<T>& block, double sigma, std::vector<float>& out,
                  const std::function<bool(double)>& progress, double from, double to) {
    const glm::ivec3 n = block.size;
    const std::vector<float> w = gaussianWeights(sigma);
    const std::size_t row = static_cast<std::size_t>(n.x), slice = row * n.y;
    out.resize(slice * n.z);
    std::vector<float> temp(out.size());
    const double step = (to - from) / 3.0;
    // Along x into out, along y into temp, along z back into out.
    const bool ok =
        parallelChunks(n.z, from, from + step, progress,
                       [&](int k) {
                           for (int j = 0; j < n.y; ++j) {
                               blurRow(out.data() + k * slice + j * row, block.row(j, k), n.x, w);
                           }
                       }) &&
        parallelChunks(n.z, from + step, from + 2 * step, progress,
                       [&](int k) {
                           for (int j = 0; j < n.y; ++j) {
                               blurLine(temp.data() + k * slice + j * row, out.data() + k * slice,
                                        row, row, j, n.y, w);
                           }
                       }) &&
        parallelChunks(n.z, from + 2 * step, to, progress, [&](int k) {
            blurLine(out.data() + k * slice, temp.data(), slice, slice, k, n.z, w);
        });
    if (!ok) {
        out.clear();
    }
    return ok;
}

template bool gaussianBlur(const VoxelBlock<std::int16_t>&, double, std::vector<float>&,
                           const std::function<bool(double)>&, double, double);
template bool gaussianBlur(const VoxelBlock<std::uint16_t>&, double, std::vector<float>&,
                           const std::function<bool(double)>&, double, double);
template bool gaussianBlur(const VoxelBlock<float>&, double, std::vector<float>&,
                           const std::function<bool(double)>&, double, double);

} // namespace lucent
