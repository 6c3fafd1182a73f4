#include "app/bench/BenchScenes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lucent::bench {

TransferFunction opacityPerUnit(TransferFunction tf, const Volume& volume, double unitMm) {
    if (unitMm > 0.0) {
        const glm::dvec3 s = volume.geometry().spacing;
        const double ratio = std::min({s.x, s.y, s.z}) / unitMm;
        for (OpacityPoint& p : tf.opacity) {
            p.opacity = 1.0 - std::pow(1.0 - p.opacity, ratio);
        }
    }
    return tf;
}

RenderDescription ctBoneScene(const Volume& volume, double unitMm, int width, int height) {
    RenderDescription d;
    d.volume = &volume;
    d.transferFunction = opacityPerUnit(loadPreset("ct-bone"), volume, unitMm);
    d.sampling.step = 0.5;
    d.sampling.interpolation = Interpolation::Linear;
    d.width = width;
    d.height = height;
    return d;
}

RenderDescription converged(const RenderDescription& d) {
    RenderDescription ref = d;
    ref.sampling.step = 1.0 / 16.0;
    ref.sampling.interpolation = Interpolation::Cubic;
    ref.sampling.precision = Precision::Double;
    return ref;
}

namespace {

template <class T> void tileVoxels(const Volume& ct, Volume& out) {
    const auto src = ct.voxels<T>();
    const auto dst = out.voxels<T>();
    const glm::ivec3 n = ct.dims(), dims = out.dims();
    const auto mirror = [](int i, int size) {
        const int period = 2 * size;
        i %= period;
        return i < size ? i : period - 1 - i;
    };
#pragma omp parallel for schedule(static)
    for (int k = 0; k < dims.z; ++k) {
        const int kk = mirror(k, n.z);
        for (int j = 0; j < dims.y; ++j) {
            const int jj = mirror(j, n.y);
            for (int i = 0; i < dims.x; ++i) {
                dst[out.linearIndex(i, j, k)] = src[ct.linearIndex(mirror(i, n.x), jj, kk)];
            }
        }
    }
}

} // namespace

Volume tiled(const Volume& ct, glm::ivec3 dims) {
    VolumeGeometry g = ct.geometry();
    g.dims = dims;
    Volume out(g, ct.type());
    out.modality = ct.modality;
    switch (ct.type()) {
    case VoxelType::Int16:
        tileVoxels<std::int16_t>(ct, out);
        break;
    case VoxelType::UInt16:
        tileVoxels<std::uint16_t>(ct, out);
        break;
    case VoxelType::Float32:
        tileVoxels<float>(ct, out);
        break;
    }
    return out;
}

double median(std::vector<double> v) {
    if (v.empty()) {
        return 0.0;
    }
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

} // namespace lucent::bench
