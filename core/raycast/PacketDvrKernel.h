#pragma once
// FastDvrKernel over eight rays at once with AVX2: positions, cells, the
// trilinear fetch and the visibility test of eight samples are one vector
// step, and the eight lattice reads of neighbouring rays overlap their cache
// misses. Each ray keeps its own lattice (t_entry + n * dt), its own leaping
// decisions and its own early termination; what a visible sample adds is
// computed per ray by FastDvrKernel's own steps, in the same order, so the
// packet kernel gives the scalar kernel's image bit for bit.
//
// Compiled for AVX2 and FMA whatever the build's target (function
// attributes); callers check packetKernelSupported() first. Private to
// core/raycast.

#include <cstdint>
#include <limits>

#include "core/raycast/FastDvrKernel.h"

namespace lucent {

// Whether this CPU runs the packet kernel (AVX2, FMA). Checked once.
bool packetKernelSupported();

template <class T> class PacketDvrKernel {
public:
    static constexpr int kWidth = 8;

    // Where FastDvrKernel applies and the volume's voxel offsets fit 32-bit lanes.
    static bool applies(const RaySetup<float>& s, glm::ivec3 dims) {
        const double voxels = double(dims.x) * double(dims.y) * double(dims.z);
        return FastDvrKernel<T>::applies(s, dims) &&
               voxels < double(std::numeric_limits<std::int32_t>::max() / 2);
    }

    PacketDvrKernel(const RaySetup<float>& s, const Grid<float, T>& g) : fast_(s, g) {}

    // count (1 .. kWidth) rays from o along d[r] (index space, per mm) with
    // unit patient-space directions w[r]; out[r] as FastDvrKernel::cast gives
    // (the packet's samples are all counted in out[0]).
    __attribute__((target("avx2,fma"))) void castPacket(const glm::dvec3& o, const glm::dvec3* d,
                                                        const glm::dvec3* w, int count,
                                                        RayOutput* out) const;

private:
    FastDvrKernel<T> fast_;
};

extern template class PacketDvrKernel<std::int16_t>;
extern template class PacketDvrKernel<std::uint16_t>;
extern template class PacketDvrKernel<float>;

} // namespace lucent
