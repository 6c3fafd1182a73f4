#include "core/formats/Nifti.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <vector>

#include <zlib.h>

#include "core/formats/RawVoxels.h"
#include "core/io/LoadControl.h"

namespace lucent {

namespace fs = std::filesystem;
using formats::RawType;

namespace {

constexpr int headerSize = 348;

struct GzClose {
    void operator()(gzFile_s* f) const { gzclose(f); }
};
using GzFile = std::unique_ptr<gzFile_s, GzClose>;

// Reads a field of the raw header, swapping bytes when the file's order differs.
class HeaderBytes {
public:
    explicit HeaderBytes(const std::array<std::byte, headerSize>& bytes) : bytes_(bytes) {}
    bool swap = false;

    template <class T> T get(std::size_t offset) const {
        std::array<std::byte, sizeof(T)> b;
        std::memcpy(b.data(), bytes_.data() + offset, sizeof(T));
        if (swap) {
            std::reverse(b.begin(), b.end());
        }
        T v;
        std::memcpy(&v, b.data(), sizeof(T));
        return v;
    }
    std::string text(std::size_t offset, std::size_t size) const {
        std::string s(reinterpret_cast<const char*>(bytes_.data()) + offset, size);
        s.resize(std::strlen(s.c_str()));
        while (!s.empty() && s.back() == ' ') {
            s.pop_back();
        }
        return s;
    }

private:
    const std::array<std::byte, headerSize>& bytes_;
};

struct Opened {
    GzFile gz;
    VolumeFileHeader header;
    RawType rawType = RawType::Int16;
    formats::Scaling scaling;
    bool bigEndian = false;
    std::uint64_t voxOffset = 352;
};

std::optional<RawType> rawTypeFor(int datatype) {
    switch (datatype) {
    case 2:
        return RawType::UInt8;
    case 256:
        return RawType::Int8;
    case 4:
        return RawType::Int16;
    case 512:
        return RawType::UInt16;
    case 8:
        return RawType::Int32;
    case 768:
        return RawType::UInt32;
    case 16:
        return RawType::Float32;
    case 64:
        return RawType::Float64;
    default:
        return std::nullopt;
    }
}

const char* datatypeName(int datatype) {
    switch (datatype) {
    case 1:
        return "binary";
    case 32:
        return "complex64";
    case 128:
        return "rgb24";
    case 1024:
        return "int64";
    case 1280:
        return "uint64";
    case 1536:
        return "float128";
    case 1792:
        return "complex128";
    case 2048:
        return "complex256";
    case 2304:
        return "rgba32";
    default:
        return "unknown";
    }
}

// The RAS affine's columns (voxel axes) and translation, by sform, qform or pixdim.
struct Affine {
    glm::dmat3 axes{1.0};
    glm::dvec3 offset{0.0};
};

Affine affineOf(const HeaderBytes& h, std::vector<std::string>& warnings) {
    std::array<double, 4> pixdim{};
    for (int i = 0; i < 4; ++i) {
        pixdim[i] = h.get<float>(76 + 4 * i);
    }
    for (int i = 1; i < 4; ++i) {
        if (!std::isfinite(pixdim[i]) || pixdim[i] == 0.0) {
            pixdim[i] = 1.0;
        }
        pixdim[i] = std::abs(pixdim[i]);
    }
    Affine a;
    if (h.get<std::int16_t>(254) > 0) { // sform_code
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) {
                a.axes[c][r] = h.get<float>(280 + 16 * r + 4 * c);
            }
            a.offset[r] = h.get<float>(280 + 16 * r + 12);
        }
        return a;
    }
    if (h.get<std::int16_t>(252) > 0) { // qform_code
        double b = h.get<float>(256);
        double c = h.get<float>(260);
        double d = h.get<float>(264);
        const double bcd = b * b + c * c + d * d;
        double q = 0.0;
        if (bcd < 1.0) {
            q = std::sqrt(1.0 - bcd);
        } else { // 180 degree rotation: normalise (b, c, d)
            const double n = std::sqrt(bcd);
            b /= n;
            c /= n;
            d /= n;
        }
        const glm::dmat3 rot(q * q + b * b - c * c - d * d, 2 * (b * c + q * d),
                             2 * (b * d - q * c), // column 0
                             2 * (b * c - q * d), q * q + c * c - b * b - d * d,
                             2 * (c * d + q * b), // column 1
                             2 * (b * d + q * c), 2 * (c * d - q * b),
                             q * q + d * d - c * c - b * b); // column 2
        const double qfac = pixdim[0] < 0.0 ? -1.0 : 1.0;
        a.axes = glm::dmat3(rot[0] * pixdim[1], rot[1] * pixdim[2], rot[2] * (pixdim[3] * qfac));
        a.offset = {h.get<float>(268), h.get<float>(272), h.get<float>(276)};
        return a;
    }
    warnings.push_back("no sform or qform: orientation unknown, pixdim scaling assumed");
    a.axes = glm::dmat3(pixdim[1], 0, 0, 0, pixdim[2], 0, 0, 0, pixdim[3]);
    return a;
}

Opened openNifti(const fs::path& path) {
    const std::string file = path.string();
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        throw LoadError(file + ": no such file");
    }
    Opened o;
    o.gz.reset(gzopen(file.c_str(), "rb"));
    if (!o.gz) {
        throw LoadError(file + ": cannot open");
    }
    std::array<std::byte, headerSize> bytes{};
    if (gzread(o.gz.get(), bytes.data(), headerSize) != headerSize) {
        throw LoadError(file + ": too short for a NIfTI-1 header (348 bytes)");
    }
    HeaderBytes h(bytes);
    const auto sizeofHdr = h.get<std::int32_t>(0);
    if (sizeofHdr != headerSize) {
        h.swap = true;
        if (h.get<std::int32_t>(0) != headerSize) {
            const bool nifti2 = sizeofHdr == 540 || h.get<std::int32_t>(0) == 540;
            throw LoadError(file + (nifti2 ? ": NIfTI-2 files are not supported"
                                           : ": not a NIfTI-1 file (sizeof_hdr is not 348)"));
        }
    }
    o.bigEndian = h.swap != (std::endian::native == std::endian::big);
    const std::string magic = h.text(344, 4);
    if (magic == "ni1") {
        throw LoadError(file + ": two-file NIfTI (.hdr/.img) is not supported");
    }
    if (magic != "n+1") {
        throw LoadError(file + ": not a NIfTI-1 file: wrong magic (expected \"n+1\")");
    }
    std::array<int, 8> dim{};
    for (int i = 0; i < 8; ++i) {
        dim[i] = h.get<std::int16_t>(40 + 2 * i);
    }
    if (dim[0] < 1 || dim[0] > 7) {
        throw LoadError(file + ": dim[0] = " + std::to_string(dim[0]) + " is out of range 1..7");
    }
    VolumeGeometry& g = o.header.geometry;
    std::uint64_t volumes = 1;
    for (int i = 1; i <= 7; ++i) {
        const int n = i <= dim[0] ? dim[i] : 1;
        if (n < 1) {
            throw LoadError(file + ": dim[" + std::to_string(i) + "] = " + std::to_string(n) +
                            " must be positive");
        }
        if (i <= 3) {
            g.dims[i - 1] = n;
        } else {
            volumes *= static_cast<std::uint64_t>(n);
        }
    }
    if (volumes > 1) {
        o.header.warnings.push_back("file holds " + std::to_string(volumes) +
                                    " volumes; only the first is read");
    }
    const int datatype = h.get<std::int16_t>(70);
    const auto raw = rawTypeFor(datatype);
    if (!raw) {
        throw LoadError(file + ": unsupported datatype " + std::to_string(datatype) + " (" +
                        datatypeName(datatype) + ")");
    }
    o.rawType = *raw;
    const double voxOffset = h.get<float>(108);
    if (!std::isfinite(voxOffset) || voxOffset < headerSize) {
        throw LoadError(file + ": vox_offset " + std::to_string(voxOffset) +
                        " lies inside the header");
    }
    if (voxOffset > 1e15) {
        throw LoadError(file + ": vox_offset " + std::to_string(voxOffset) +
                        " is implausibly large");
    }
    o.voxOffset = static_cast<std::uint64_t>(voxOffset);
    const double slope = h.get<float>(112);
    const double inter = h.get<float>(116);
    if (std::isfinite(slope) && slope != 0.0) {
        o.scaling = {slope, std::isfinite(inter) ? inter : 0.0};
    }
    o.header.voxelType = formats::volumeTypeFor(o.rawType, o.scaling);

    const Affine a = affineOf(h, o.header.warnings);
    const glm::dvec3 rasToLps(-1.0, -1.0, 1.0);
    for (int c = 0; c < 3; ++c) {
        const glm::dvec3 axis = a.axes[c] * rasToLps;
        g.spacing[c] = glm::length(axis);
        g.direction[c] = g.spacing[c] > 0.0 ? axis / g.spacing[c] : axis;
    }
    g.origin = a.offset * rasToLps;
    g = formats::checkedGeometry(g, file);
    o.header.description = h.text(148, 80);
    return o;
}

} // namespace

VolumeFileHeader readNiftiHeader(const fs::path& path) {
    return openNifti(path).header;
}

Volume readNifti(const fs::path& path) {
    Opened o = openNifti(path);
    const std::string file = path.string();
    gzFile gz = o.gz.get();
    const auto read = [gz, &file](std::span<std::byte> b) -> std::size_t {
        const auto n = static_cast<unsigned>(std::min<std::size_t>(b.size(), 1u << 30));
        const int got = gzread(gz, b.data(), n);
        if (got < 0) {
            int code = 0;
            throw LoadError(file + ": read error (" + gzerror(gz, &code) + ")");
        }
        return static_cast<std::size_t>(got);
    };
    const std::uint64_t bytes = o.header.geometry.voxelCount() * formats::rawTypeSize(o.rawType);
    if (gzdirect(gz)) { // not compressed: check the size before allocating
        std::error_code ec;
        const std::uint64_t size = fs::file_size(path, ec);
        if (!ec && size < o.voxOffset + bytes) {
            throw LoadError(file + ": voxel data truncated: expected " + std::to_string(bytes) +
                            " bytes after offset " + std::to_string(o.voxOffset) + ", file has " +
                            std::to_string(size) + " bytes in all");
        }
    }
    std::vector<std::byte> skip(std::size_t{1} << 16);
    for (std::uint64_t left = o.voxOffset - headerSize; left > 0;) {
        const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(left, skip.size()));
        if (read(std::span(skip).first(n)) != n) {
            throw LoadError(file + ": file ends before vox_offset");
        }
        left -= n;
    }
    Volume volume = formats::allocateVolume(o.header.geometry, o.header.voxelType, file);
    formats::readVoxels(read, o.rawType, o.bigEndian, o.scaling, volume, file);
    volume.description = o.header.description;
    volume.warnings = o.header.warnings;
    return volume;
}

} // namespace lucent
