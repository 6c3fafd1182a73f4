#include "core/formats/RawVoxels.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <new>
#include <type_traits>
#include <vector>

#include <zlib.h>

#include "core/io/LoadControl.h"

namespace lucent::formats {

namespace {

template <class Src> Src loadElement(const std::byte* p, bool swap) {
    std::array<std::byte, sizeof(Src)> b;
    std::memcpy(b.data(), p, sizeof(Src));
    if (swap) {
        std::reverse(b.begin(), b.end());
    }
    Src v;
    std::memcpy(&v, b.data(), sizeof(Src));
    return v;
}

template <class Src, class Dst>
void convertChunk(const std::byte* src, std::size_t n, bool swap, const Scaling& s, Dst* dst) {
    const bool identity = s.identity();
    for (std::size_t i = 0; i < n; ++i) {
        const Src v = loadElement<Src>(src + i * sizeof(Src), swap);
        if (identity) {
            dst[i] = static_cast<Dst>(v);
            continue;
        }
        const double x = static_cast<double>(v) * s.slope + s.inter;
        if constexpr (std::is_integral_v<Dst>) {
            dst[i] = static_cast<Dst>(std::nearbyint(x));
        } else {
            dst[i] = static_cast<Dst>(x);
        }
    }
}

template <class Dst>
void convertTo(RawType type, const std::byte* src, std::size_t n, bool swap, const Scaling& s,
               Dst* dst) {
    switch (type) {
    case RawType::UInt8:
        return convertChunk<std::uint8_t>(src, n, swap, s, dst);
    case RawType::Int8:
        return convertChunk<std::int8_t>(src, n, swap, s, dst);
    case RawType::Int16:
        return convertChunk<std::int16_t>(src, n, swap, s, dst);
    case RawType::UInt16:
        return convertChunk<std::uint16_t>(src, n, swap, s, dst);
    case RawType::Int32:
        return convertChunk<std::int32_t>(src, n, swap, s, dst);
    case RawType::UInt32:
        return convertChunk<std::uint32_t>(src, n, swap, s, dst);
    case RawType::Float32:
        return convertChunk<float>(src, n, swap, s, dst);
    case RawType::Float64:
        return convertChunk<double>(src, n, swap, s, dst);
    }
}

// Reads until dst is full or the source ends; returns the bytes read.
std::size_t readFully(const ByteReader& read, std::span<std::byte> dst) {
    std::size_t done = 0;
    while (done < dst.size()) {
        const std::size_t n = read(dst.subspan(done));
        if (n == 0) {
            break;
        }
        done += n;
    }
    return done;
}

[[noreturn]] void throwShort(const std::string& fileLabel, std::size_t expected, std::size_t got) {
    throw LoadError(fileLabel + ": voxel data truncated: expected " + std::to_string(expected) +
                    " bytes, found " + std::to_string(got));
}

} // namespace

std::size_t rawTypeSize(RawType type) {
    switch (type) {
    case RawType::UInt8:
    case RawType::Int8:
        return 1;
    case RawType::Int16:
    case RawType::UInt16:
        return 2;
    case RawType::Int32:
    case RawType::UInt32:
    case RawType::Float32:
        return 4;
    case RawType::Float64:
        return 8;
    }
    return 1;
}

const char* rawTypeName(RawType type) {
    switch (type) {
    case RawType::UInt8:
        return "uint8";
    case RawType::Int8:
        return "int8";
    case RawType::Int16:
        return "int16";
    case RawType::UInt16:
        return "uint16";
    case RawType::Int32:
        return "int32";
    case RawType::UInt32:
        return "uint32";
    case RawType::Float32:
        return "float32";
    case RawType::Float64:
        return "float64";
    }
    return "?";
}

bool isIntegerType(RawType type) {
    return type != RawType::Float32 && type != RawType::Float64;
}

VoxelType volumeTypeFor(RawType type, const Scaling& scaling) {
    const auto natural = [type] {
        switch (type) {
        case RawType::UInt8:
        case RawType::Int8:
        case RawType::Int16:
            return VoxelType::Int16;
        case RawType::UInt16:
            return VoxelType::UInt16;
        default:
            return VoxelType::Float32;
        }
    }();
    if (scaling.identity() || !isIntegerType(type)) {
        return natural;
    }
    if (std::trunc(scaling.slope) != scaling.slope || std::trunc(scaling.inter) != scaling.inter) {
        return VoxelType::Float32;
    }
    const auto [lo, hi] = [type]() -> std::pair<double, double> {
        switch (type) {
        case RawType::UInt8:
            return {0.0, 255.0};
        case RawType::Int8:
            return {-128.0, 127.0};
        case RawType::Int16:
            return {-32768.0, 32767.0};
        case RawType::UInt16:
            return {0.0, 65535.0};
        case RawType::Int32:
            return {-2147483648.0, 2147483647.0};
        default:
            return {0.0, 4294967295.0}; // UInt32; floats returned above
        }
    }();
    const double a = lo * scaling.slope + scaling.inter;
    const double b = hi * scaling.slope + scaling.inter;
    const double mn = std::min(a, b);
    const double mx = std::max(a, b);
    if (mn >= -32768.0 && mx <= 32767.0) {
        return VoxelType::Int16;
    }
    if (mn >= 0.0 && mx <= 65535.0) {
        return VoxelType::UInt16;
    }
    return VoxelType::Float32;
}

void readVoxels(const ByteReader& read, RawType type, bool bigEndian, const Scaling& scaling,
                Volume& dst, const std::string& fileLabel) {
    const bool swap = bigEndian != (std::endian::native == std::endian::big);
    const std::size_t elemSize = rawTypeSize(type);
    const std::size_t count = dst.geometry().voxelCount();
    const std::size_t expected = count * elemSize;
    const bool direct = !swap && scaling.identity() &&
                        ((type == RawType::Int16 && dst.type() == VoxelType::Int16) ||
                         (type == RawType::UInt16 && dst.type() == VoxelType::UInt16) ||
                         (type == RawType::Float32 && dst.type() == VoxelType::Float32));
    if (direct) {
        const std::size_t got = readFully(read, dst.bytes());
        if (got != expected) {
            throwShort(fileLabel, expected, got);
        }
        return;
    }
    constexpr std::size_t chunkElements = std::size_t{1} << 18;
    std::vector<std::byte> buffer(chunkElements * elemSize);
    std::size_t done = 0;
    while (done < count) {
        const std::size_t n = std::min(chunkElements, count - done);
        const std::size_t got = readFully(read, std::span(buffer).first(n * elemSize));
        if (got != n * elemSize) {
            throwShort(fileLabel, expected, done * elemSize + got);
        }
        visitVoxels(dst, [&](auto voxels) {
            convertTo(type, buffer.data(), n, swap, scaling, voxels.data() + done);
        });
        done += n;
    }
}

struct InflateReader::State {
    ByteReader input;
    std::string file;
    z_stream zs{};
    std::vector<std::byte> buffer = std::vector<std::byte>(std::size_t{1} << 16);
    bool inputEnded = false;
    bool ended = false;
};

InflateReader::InflateReader(ByteReader input, std::string fileLabel)
    : state_(std::make_unique<State>()) {
    state_->input = std::move(input);
    state_->file = std::move(fileLabel);
    if (inflateInit2(&state_->zs, 15 + 32) != Z_OK) { // zlib or gzip header
        throw LoadError(state_->file + ": cannot start zlib");
    }
}

InflateReader::~InflateReader() {
    inflateEnd(&state_->zs);
}

std::size_t InflateReader::read(std::span<std::byte> dst) {
    State& s = *state_;
    s.zs.next_out = reinterpret_cast<Bytef*>(dst.data());
    s.zs.avail_out = static_cast<uInt>(std::min<std::size_t>(dst.size(), std::size_t{1} << 30));
    const uInt wanted = s.zs.avail_out;
    while (s.zs.avail_out > 0 && !s.ended) {
        if (s.zs.avail_in == 0 && !s.inputEnded) {
            const std::size_t got = s.input(s.buffer);
            s.inputEnded = got == 0;
            s.zs.next_in = reinterpret_cast<Bytef*>(s.buffer.data());
            s.zs.avail_in = static_cast<uInt>(got);
        }
        const int rc = inflate(&s.zs, Z_NO_FLUSH);
        if (rc == Z_STREAM_END) {
            s.ended = true;
        } else if (rc == Z_BUF_ERROR && s.zs.avail_in == 0 && s.inputEnded) {
            break; // the compressed data end early; the caller reports truncation
        } else if (rc != Z_OK && rc != Z_BUF_ERROR) {
            throw LoadError(s.file + ": corrupt compressed voxel data (" +
                            (s.zs.msg ? s.zs.msg : "zlib error") + ")");
        }
    }
    return wanted - s.zs.avail_out;
}

Volume allocateVolume(const VolumeGeometry& geometry, VoxelType type,
                      const std::string& fileLabel) {
    const glm::ivec3 d = geometry.dims;
    if (d.x <= 0 || d.y <= 0 || d.z <= 0) {
        throw LoadError(fileLabel + ": dimensions must be positive");
    }
    const double bytes = static_cast<double>(d.x) * d.y * d.z * voxelSize(type);
    if (bytes > static_cast<double>(std::size_t{1} << 40)) {
        throw LoadError(fileLabel + ": implausible volume size " + std::to_string(d.x) + "x" +
                        std::to_string(d.y) + "x" + std::to_string(d.z));
    }
    try {
        return Volume(geometry, type);
    } catch (const std::bad_alloc&) {
        throw LoadError(fileLabel + ": not enough memory for a " + std::to_string(d.x) + "x" +
                        std::to_string(d.y) + "x" + std::to_string(d.z) + " volume");
    }
}

VolumeGeometry checkedGeometry(VolumeGeometry geometry, const std::string& fileLabel) {
    static const char* const axes[] = {"i", "j", "k"};
    for (int c = 0; c < 3; ++c) {
        const double len = glm::length(geometry.direction[c]);
        if (!std::isfinite(len) || len < 1e-9) {
            throw LoadError(fileLabel + ": direction of the " + axes[c] + " axis is degenerate");
        }
        geometry.direction[c] /= len;
        if (!std::isfinite(geometry.spacing[c]) || geometry.spacing[c] <= 0.0) {
            throw LoadError(fileLabel + ": spacing of the " + axes[c] +
                            " axis must be positive, is " + std::to_string(geometry.spacing[c]));
        }
        if (!std::isfinite(geometry.origin[c])) {
            throw LoadError(fileLabel + ": origin is not a finite number");
        }
    }
    return geometry;
}

} // namespace lucent::formats
