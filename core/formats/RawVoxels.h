#pragma once

// Internal to core/formats: decoding raw voxel streams into a Volume.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>

#include "core/volume/Volume.h"

namespace lucent::formats {

// Element types found in volume files.
enum class RawType { UInt8, Int8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::size_t rawTypeSize(RawType type);
const char* rawTypeName(RawType type);
bool isIntegerType(RawType type);

// value * slope + inter, applied when not the identity.
struct Scaling {
    double slope = 1.0;
    double inter = 0.0;
    bool identity() const { return slope == 1.0 && inter == 0.0; }
};

// The volume type a raw type is loaded as: uint8, int8 and int16 -> Int16,
// uint16 -> UInt16, everything else -> Float32. With a scaling, an integer type
// keeps an integer volume type only when every value of the raw type maps exactly
// into it (integral slope and intercept, scaled range inside int16 or uint16).
VoxelType volumeTypeFor(RawType type, const Scaling& scaling = {});

// Reads up to dst.size() bytes; returns how many were read (fewer only at the end).
// Throws LoadError on a read error.
using ByteReader = std::function<std::size_t(std::span<std::byte>)>;

// Fills every voxel of dst (i fastest) from read, converting from type with the
// given byte order and scaling. Throws LoadError naming fileLabel when the data
// end early.
void readVoxels(const ByteReader& read, RawType type, bool bigEndian, const Scaling& scaling,
                Volume& dst, const std::string& fileLabel);

// zlib or gzip decompression of a byte stream, itself a ByteReader source.
class InflateReader {
public:
    InflateReader(ByteReader input, std::string fileLabel);
    ~InflateReader();
    InflateReader(const InflateReader&) = delete;
    InflateReader& operator=(const InflateReader&) = delete;

    // Returns fewer bytes than asked only where the compressed data end.
    std::size_t read(std::span<std::byte> dst);

private:
    struct State;
    std::unique_ptr<State> state_;
};

// Allocates a volume, turning absurd sizes and allocation failures into LoadError.
Volume allocateVolume(const VolumeGeometry& geometry, VoxelType type, const std::string& fileLabel);

// Throws LoadError when the direction columns are not usable (zero, not finite);
// returns the geometry with unit direction columns.
VolumeGeometry checkedGeometry(VolumeGeometry geometry, const std::string& fileLabel);

} // namespace lucent::formats
