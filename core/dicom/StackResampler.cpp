#include "core/dicom/StackResampler.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace lucent {
namespace {

constexpr double kEps = 1e-6;

template <class T>
double bilinear(const T* img, int cols, int rows, double a, double b, double pad) {
    if (a < -kEps || b < -kEps || a > cols - 1 + kEps || b > rows - 1 + kEps) {
        return pad;
    }
    a = std::clamp(a, 0.0, static_cast<double>(cols - 1));
    b = std::clamp(b, 0.0, static_cast<double>(rows - 1));
    const int a0 = std::min(static_cast<int>(a), std::max(cols - 2, 0));
    const int b0 = std::min(static_cast<int>(b), std::max(rows - 2, 0));
    const double fa = a - a0;
    const double fb = b - b0;
    const int a1 = std::min(a0 + 1, cols - 1);
    const int b1 = std::min(b0 + 1, rows - 1);
    const auto at = [&](int x, int y) {
        return static_cast<double>(img[x + std::size_t(cols) * y]);
    };
    return (1 - fb) * ((1 - fa) * at(a0, b0) + fa * at(a1, b0)) +
           fb * ((1 - fa) * at(a0, b1) + fa * at(a1, b1));
}

template <class T>
void resampleTyped(std::span<const T> src, const glm::ivec3& srcDims, const StackPlan& plan,
                   double pad, std::span<T> dst, const glm::ivec3& dims) {
    const std::size_t slice = std::size_t(srcDims.x) * srcDims.y;
    const int images = srcDims.z;
#pragma omp parallel for schedule(dynamic)
    for (int k = 0; k < dims.z; ++k) {
        // The images on either side of this grid slice along the normal.
        int hi = 0;
        while (hi < images && plan.placement[hi].z < k - kEps) {
            ++hi;
        }
        int lo = hi;
        double w = 0.0;
        if (hi < images && std::abs(plan.placement[hi].z - k) <= kEps) {
            lo = hi; // lands on an image
        } else if (hi > 0 && hi < images) {
            lo = hi - 1;
            w = (k - plan.placement[lo].z) / (plan.placement[hi].z - plan.placement[lo].z);
        } else {
            lo = hi = std::clamp(hi, 0, images - 1);
        }
        const T* imgLo = src.data() + slice * lo;
        const T* imgHi = src.data() + slice * hi;
        const glm::dvec3 pLo = plan.placement[lo];
        const glm::dvec3 pHi = plan.placement[hi];
        T* out = dst.data() + std::size_t(dims.x) * dims.y * k;
        for (int j = 0; j < dims.y; ++j) {
            for (int i = 0; i < dims.x; ++i) {
                double v = bilinear(imgLo, srcDims.x, srcDims.y, i - pLo.x, j - pLo.y, pad);
                if (w > 0.0) {
                    const double vHi =
                        bilinear(imgHi, srcDims.x, srcDims.y, i - pHi.x, j - pHi.y, pad);
                    v = (1.0 - w) * v + w * vHi;
                }
                if constexpr (std::is_integral_v<T>) {
                    out[i + std::size_t(dims.x) * j] = static_cast<T>(std::lround(v));
                } else {
                    out[i + std::size_t(dims.x) * j] = static_cast<T>(v);
                }
            }
        }
    }
}

} // namespace

Volume resampleStack(const Volume& stack, const StackPlan& plan, double padValue) {
    Volume out(plan.geometry, stack.type());
    visitVoxels(stack, [&](auto src) {
        using T = std::remove_const_t<typename decltype(src)::element_type>;
        resampleTyped<T>(src, stack.dims(), plan, padValue, out.voxels<T>(), plan.geometry.dims);
    });
    return out;
}

} // namespace lucent
