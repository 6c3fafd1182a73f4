#pragma once

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/volume/SeriesInfo.h"

namespace lucent {

enum class VoxelType { Int16, UInt16, Float32 };

std::size_t voxelSize(VoxelType type);
const char* voxelTypeName(VoxelType type);

// Where a volume's voxels sit in the patient: an index (i, j, k) maps to
// origin + direction * (spacing * ijk), in LPS millimetres. The columns of
// direction are the unit vectors of the i, j and k axes.
struct VolumeGeometry {
    glm::ivec3 dims{0};
    glm::dvec3 spacing{1.0};
    glm::dvec3 origin{0.0};
    glm::dmat3 direction{1.0};

    glm::dmat4 indexToPatient() const;
    glm::dmat4 patientToIndex() const;
    glm::dvec3 toPatient(const glm::dvec3& ijk) const;
    glm::dvec3 toIndex(const glm::dvec3& lps) const;
    std::size_t voxelCount() const;
};

// The centre of the volume's box (the midpoint of its first and last voxel
// centres), in LPS mm.
glm::dvec3 volumeCentre(const VolumeGeometry& geometry);

// A scalar volume: voxels in one typed buffer, i fastest, then j, then k.
// CT voxels hold Hounsfield units (rescale applied). Move-only: a volume can
// be gigabytes and must never be copied by accident.
class Volume : public SeriesInfo { // what the volume is, for people and the overlays
public:
    Volume() = default;
    Volume(const VolumeGeometry& geometry, VoxelType type);
    Volume(Volume&&) noexcept = default;
    Volume& operator=(Volume&&) noexcept = default;
    Volume(const Volume&) = delete;
    Volume& operator=(const Volume&) = delete;

    const VolumeGeometry& geometry() const { return geometry_; }
    void setGeometry(const VolumeGeometry& geometry);
    const glm::ivec3& dims() const { return geometry_.dims; }
    VoxelType type() const { return type_; }
    bool empty() const { return geometry_.voxelCount() == 0; }

    std::span<std::byte> bytes() { return {data_.get(), byteCount()}; }
    std::span<const std::byte> bytes() const { return {data_.get(), byteCount()}; }
    std::size_t byteCount() const { return geometry_.voxelCount() * voxelSize(type_); }

    // Typed view; T must match type().
    template <class T> std::span<T> voxels();
    template <class T> std::span<const T> voxels() const;

    std::size_t linearIndex(int i, int j, int k) const {
        return static_cast<std::size_t>(i) +
               static_cast<std::size_t>(geometry_.dims.x) *
                   (static_cast<std::size_t>(j) +
                    static_cast<std::size_t>(geometry_.dims.y) * static_cast<std::size_t>(k));
    }
    double value(int i, int j, int k) const;
    // Smallest and largest voxel value (computed on demand, not cached).
    std::pair<double, double> valueRange() const;

    // What was done to build it and what the user should know (tilt, gaps, ...).
    std::vector<std::string> warnings;

private:
    void checkType(VoxelType wanted) const;

    struct FreeDeleter {
        void operator()(std::byte* p) const;
    };

    VolumeGeometry geometry_;
    VoxelType type_ = VoxelType::Int16;
    std::unique_ptr<std::byte[], FreeDeleter> data_;
};

template <class T> struct VoxelTypeOf;
template <> struct VoxelTypeOf<std::int16_t> {
    static constexpr VoxelType value = VoxelType::Int16;
};
template <> struct VoxelTypeOf<std::uint16_t> {
    static constexpr VoxelType value = VoxelType::UInt16;
};
template <> struct VoxelTypeOf<float> { static constexpr VoxelType value = VoxelType::Float32; };

template <class T> std::span<T> Volume::voxels() {
    checkType(VoxelTypeOf<std::remove_const_t<T>>::value);
    return {reinterpret_cast<T*>(data_.get()), geometry_.voxelCount()};
}

template <class T> std::span<const T> Volume::voxels() const {
    checkType(VoxelTypeOf<std::remove_const_t<T>>::value);
    return {reinterpret_cast<const T*>(data_.get()), geometry_.voxelCount()};
}

// Calls f with a typed span of the volume's voxels (int16_t, uint16_t or float;
// const when the volume is).
template <class V, class F>
requires std::same_as<std::remove_const_t<V>, Volume>
decltype(auto) visitVoxels(V& volume, F&& f) {
    using Out = std::conditional_t<std::is_const_v<V>, const Volume, Volume>;
    Out& v = volume;
    switch (v.type()) {
    case VoxelType::Int16:
        return f(v.template voxels<std::int16_t>());
    case VoxelType::UInt16:
        return f(v.template voxels<std::uint16_t>());
    case VoxelType::Float32:
        break;
    }
    return f(v.template voxels<float>());
}

} // namespace lucent
