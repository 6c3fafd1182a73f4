#include "core/volume/Volume.h"

#include <algorithm>
#include <cstdlib>
#include <new>

#include <limits>
#include <stdexcept>
#include <sys/mman.h>

namespace lucent {

glm::dvec3 volumeCentre(const VolumeGeometry& g) {
    return g.toPatient(0.5 * glm::dvec3(g.dims - 1));
}

std::size_t voxelSize(VoxelType type) {
    switch (type) {
    case VoxelType::Int16:
    case VoxelType::UInt16:
        return 2;
    case VoxelType::Float32:
        return 4;
    }
    return 0;
}

const char* voxelTypeName(VoxelType type) {
    switch (type) {
    case VoxelType::Int16:
        return "int16";
    case VoxelType::UInt16:
        return "uint16";
    case VoxelType::Float32:
        return "float32";
    }
    return "?";
}

glm::dmat4 VolumeGeometry::indexToPatient() const {
    glm::dmat4 m(1.0);
    for (int c = 0; c < 3; ++c) {
        m[c] = glm::dvec4(direction[c] * spacing[c], 0.0);
    }
    m[3] = glm::dvec4(origin, 1.0);
    return m;
}

glm::dmat4 VolumeGeometry::patientToIndex() const {
    return glm::inverse(indexToPatient());
}

glm::dvec3 VolumeGeometry::toPatient(const glm::dvec3& ijk) const {
    return origin + direction * (spacing * ijk);
}

glm::dvec3 VolumeGeometry::toIndex(const glm::dvec3& lps) const {
    return glm::dvec3(patientToIndex() * glm::dvec4(lps, 1.0));
}

std::size_t VolumeGeometry::voxelCount() const {
    if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0) {
        return 0;
    }
    return static_cast<std::size_t>(dims.x) * static_cast<std::size_t>(dims.y) *
           static_cast<std::size_t>(dims.z);
}

Volume::Volume(const VolumeGeometry& geometry, VoxelType type) : geometry_(geometry), type_(type) {
    if (geometry.dims.x <= 0 || geometry.dims.y <= 0 || geometry.dims.z <= 0) {
        throw std::invalid_argument("volume dimensions must be positive");
    }
    // Left uninitialised on purpose: every loader writes every voxel, and
    // clearing gigabytes first costs real time. Large volumes sit on 2 MiB
    // pages where the kernel allows it: first touch of a 512^2 x 140 CT then
    // costs tens of page faults instead of tens of thousands.
    constexpr std::size_t kHugePage = std::size_t(2) << 20;
    const std::size_t bytes = byteCount();
    const bool huge = bytes >= 4 * kHugePage;
    const std::size_t alignment = huge ? kHugePage : 64;
    const std::size_t rounded = (bytes + alignment - 1) / alignment * alignment;
    auto* p = static_cast<std::byte*>(std::aligned_alloc(alignment, rounded));
    if (p == nullptr) {
        throw std::bad_alloc();
    }
    if (huge) {
        ::madvise(p, rounded, MADV_HUGEPAGE); // advice only: failure changes nothing
    }
    data_.reset(p);
}

void Volume::FreeDeleter::operator()(std::byte* p) const {
    std::free(p);
}

void Volume::setGeometry(const VolumeGeometry& geometry) {
    if (geometry.dims != geometry_.dims) {
        throw std::invalid_argument("setGeometry cannot change the dimensions of a volume");
    }
    geometry_ = geometry;
}

void Volume::checkType(VoxelType wanted) const {
    if (wanted != type_) {
        throw std::logic_error(std::string("volume holds ") + voxelTypeName(type_) + ", not " +
                               voxelTypeName(wanted));
    }
}

double Volume::value(int i, int j, int k) const {
    const std::size_t n = linearIndex(i, j, k);
    return visitVoxels(*this, [n](auto v) { return static_cast<double>(v[n]); });
}

std::pair<double, double> Volume::valueRange() const {
    if (empty()) {
        return {0.0, 0.0};
    }
    return visitVoxels(*this, [](auto v) {
        const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
        return std::pair<double, double>(*lo, *hi);
    });
}

} // namespace lucent
