#include "core/formats/NiftiWrite.h"

#include <array>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <zlib.h>

#include "core/formats/AtomicFile.h"

namespace lucent {
namespace {

constexpr int kHeaderSize = 348;
constexpr int kDataOffset = 352; // the header and 4 bytes of no extension

template <class T> void put(std::vector<char>& h, int offset, T value) {
    std::memcpy(h.data() + offset, &value, sizeof value);
}

std::vector<char> header(const Volume& volume) {
    std::vector<char> h(kDataOffset, 0);
    const VolumeGeometry& g = volume.geometry();
    put<std::int32_t>(h, 0, kHeaderSize);
    const std::array<std::int16_t, 8> dim{
        3, std::int16_t(g.dims.x), std::int16_t(g.dims.y), std::int16_t(g.dims.z), 1, 1, 1, 1};
    for (int i = 0; i < 8; ++i) {
        put<std::int16_t>(h, 40 + 2 * i, dim[i]);
    }
    const auto [datatype, bitpix] = [&]() -> std::pair<std::int16_t, std::int16_t> {
        switch (volume.type()) {
        case VoxelType::Int16:
            return {4, 16};
        case VoxelType::UInt16:
            return {512, 16};
        case VoxelType::Float32:
            break;
        }
        return {16, 32};
    }();
    put<std::int16_t>(h, 70, datatype);
    put<std::int16_t>(h, 72, bitpix);
    const std::array<float, 4> pixdim{1.0f, float(g.spacing.x), float(g.spacing.y),
                                      float(g.spacing.z)};
    for (int i = 0; i < 4; ++i) {
        put<float>(h, 76 + 4 * i, pixdim[i]);
    }
    put<float>(h, 108, float(kDataOffset)); // vox_offset
    put<float>(h, 112, 1.0f);               // scl_slope
    h[123] = 2;                             // xyzt_units: mm
    std::strncpy(h.data() + 148, "Lucent", 79);
    put<std::int16_t>(h, 254, 2); // sform_code: aligned to another file
    // LPS index -> patient, then RAS = (-x, -y, z).
    const glm::dmat4 m = g.indexToPatient();
    for (int r = 0; r < 3; ++r) {
        const double flip = r < 2 ? -1.0 : 1.0;
        for (int c = 0; c < 4; ++c) {
            put<float>(h, 280 + 16 * r + 4 * c, float(flip * m[c][r]));
        }
    }
    std::memcpy(h.data() + 344, "n+1\0", 4);
    return h;
}

std::vector<char> gzipped(const std::vector<char>& plain, const std::filesystem::path& path) {
    z_stream z{};
    if (deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
        throw std::runtime_error(path.string() + ": gzip cannot start");
    }
    std::vector<char> out(deflateBound(&z, plain.size()));
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(plain.data()));
    z.avail_in = static_cast<uInt>(plain.size());
    z.next_out = reinterpret_cast<Bytef*>(out.data());
    z.avail_out = static_cast<uInt>(out.size());
    const int done = deflate(&z, Z_FINISH);
    out.resize(z.total_out);
    deflateEnd(&z);
    if (done != Z_STREAM_END) {
        throw std::runtime_error(path.string() + ": gzip failed");
    }
    return out;
}

} // namespace

void writeNifti(const std::filesystem::path& path, const Volume& volume) {
    if (volume.empty()) {
        throw std::runtime_error(path.string() + ": an empty volume cannot be written");
    }
    if (volume.dims().x > 32767 || volume.dims().y > 32767 || volume.dims().z > 32767) {
        throw std::runtime_error(path.string() + ": NIfTI-1 holds at most 32767 voxels an axis");
    }
    std::vector<char> bytes = header(volume);
    const std::span<const std::byte> voxels = volume.bytes();
    bytes.insert(bytes.end(), reinterpret_cast<const char*>(voxels.data()),
                 reinterpret_cast<const char*>(voxels.data()) + voxels.size());
    if (path.extension() == ".gz") {
        if (bytes.size() > 0xffffffffu) {
            throw std::runtime_error(path.string() + ": too large to gzip in one piece");
        }
        bytes = gzipped(bytes, path);
    }
    formats::AtomicFileWriter file(path);
    file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    file.finish();
    file.commit();
}

} // namespace lucent
