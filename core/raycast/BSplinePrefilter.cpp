#include "core/raycast/BSplinePrefilter.h"

#include <cmath>

namespace lucent {
namespace {

// In-place prefilter of one line of n samples spaced `stride` apart.
template <class Real> void filterLine(Real* c, int n, std::size_t stride) {
    if (n < 2) {
        return;
    }
    const double z = std::sqrt(3.0) - 2.0;
    const double lambda = (1.0 - z) * (1.0 - 1.0 / z); // gain 6
    auto at = [&](int i) -> Real& { return c[stride * static_cast<std::size_t>(i)]; };
    for (int i = 0; i < n; ++i) {
        at(i) = static_cast<Real>(at(i) * lambda);
    }
    // Causal initialisation for mirror boundaries: exact for lines shorter
    // than the horizon where z^k becomes negligible, truncated beyond it.
    const int horizon = static_cast<int>(std::ceil(std::log(1e-16) / std::log(std::abs(z))));
    double sum = 0.0;
    if (n <= horizon) {
        const double z2n = std::pow(z, 2 * n - 2);
        double zk = z;
        sum = at(0) + std::pow(z, n - 1) * at(n - 1);
        for (int k = 1; k < n - 1; ++k) {
            sum += (zk + z2n / zk) * at(k);
            zk *= z;
        }
        sum /= 1.0 - z2n;
    } else {
        double zk = 1.0;
        for (int k = 0; k < horizon; ++k) {
            sum += zk * at(k);
            zk *= z;
        }
    }
    at(0) = static_cast<Real>(sum);
    for (int i = 1; i < n; ++i) {
        at(i) = static_cast<Real>(at(i) + z * at(i - 1));
    }
    // Anticausal initialisation and pass.
    at(n - 1) = static_cast<Real>((z / (z * z - 1.0)) * (z * at(n - 2) + at(n - 1)));
    for (int i = n - 2; i >= 0; --i) {
        at(i) = static_cast<Real>(z * (at(i + 1) - at(i)));
    }
}

} // namespace

template <class Real> std::vector<Real> bsplineCoefficients(const Volume& volume) {
    const glm::ivec3 d = volume.dims();
    std::vector<Real> c(volume.geometry().voxelCount());
    visitVoxels(volume, [&](auto v) {
        for (std::size_t i = 0; i < v.size(); ++i) {
            c[i] = static_cast<Real>(v[i]);
        }
    });
    const std::size_t sx = 1, sy = std::size_t(d.x), sz = std::size_t(d.x) * d.y;
#pragma omp parallel for schedule(static)
    for (int k = 0; k < d.z; ++k) {
        for (int j = 0; j < d.y; ++j) {
            filterLine(c.data() + sz * k + sy * j, d.x, sx);
        }
        for (int i = 0; i < d.x; ++i) {
            filterLine(c.data() + sz * k + i, d.y, sy);
        }
    }
#pragma omp parallel for schedule(static)
    for (int j = 0; j < d.y; ++j) {
        for (int i = 0; i < d.x; ++i) {
            filterLine(c.data() + sy * j + i, d.z, sz);
        }
    }
    return c;
}

template std::vector<float> bsplineCoefficients<float>(const Volume&);
template std::vector<double> bsplineCoefficients<double>(const Volume&);

} // namespace lucent
