#include "core/formats/MetaImage.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <string_view>
#include <vector>

#include "core/formats/RawVoxels.h"
#include "core/io/LoadControl.h"

namespace lucent {

namespace fs = std::filesystem;
using formats::RawType;

namespace {

constexpr std::size_t maxHeaderBytes = std::size_t{1} << 20;

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) {
        s.remove_prefix(1);
    }
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) {
        s.remove_suffix(1);
    }
    return s;
}

bool iequals(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) ==
                      std::tolower(static_cast<unsigned char>(y));
           });
}

// The parsed "Key = Value" lines of a MetaImage header.
struct MetaHeader {
    std::string file;
    std::vector<std::pair<std::string, std::string>> fields;
    std::size_t dataOffset = 0; // where LOCAL data start in the header file

    const std::string* find(std::initializer_list<std::string_view> names) const {
        for (const auto name : names) {
            for (const auto& [key, value] : fields) {
                if (iequals(key, name)) {
                    return &value;
                }
            }
        }
        return nullptr;
    }

    [[noreturn]] void fail(std::string_view key, const std::string& what) const {
        throw LoadError(file + ": " + std::string(key) + ": " + what);
    }

    std::vector<double> numbers(std::initializer_list<std::string_view> names, std::size_t count,
                                std::vector<double> fallback) const {
        const std::string* value = find(names);
        if (!value) {
            return fallback;
        }
        std::vector<double> out;
        const char* p = value->data();
        const char* end = p + value->size();
        while (p < end) {
            while (p < end && std::isspace(static_cast<unsigned char>(*p))) {
                ++p;
            }
            if (p == end) {
                break;
            }
            double x = 0.0;
            const auto [next, ec] = std::from_chars(p, end, x);
            if (ec != std::errc() || !std::isfinite(x)) {
                fail(*names.begin(), "not a number list: '" + *value + "'");
            }
            out.push_back(x);
            p = next;
        }
        if (out.size() != count) {
            fail(*names.begin(), "expected " + std::to_string(count) + " numbers, found " +
                                     std::to_string(out.size()));
        }
        return out;
    }

    bool flag(std::initializer_list<std::string_view> names) const {
        const std::string* value = find(names);
        if (!value) {
            return false;
        }
        if (iequals(*value, "true") || *value == "1") {
            return true;
        }
        if (iequals(*value, "false") || *value == "0") {
            return false;
        }
        fail(*names.begin(), "expected True or False, found '" + *value + "'");
    }
};

MetaHeader parseHeader(const fs::path& path) {
    MetaHeader h;
    h.file = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw LoadError(h.file + ": cannot open (" +
                        (fs::exists(path) ? "permission denied?" : "no such file") + ")");
    }
    // The header is read up to 1 MiB; a small file costs its own size, not that.
    std::error_code sizeError;
    const std::uintmax_t fileSize = fs::file_size(path, sizeError);
    std::string text(
        sizeError ? maxHeaderBytes
                  : static_cast<std::size_t>(std::min<std::uintmax_t>(fileSize, maxHeaderBytes)),
        '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    std::size_t pos = 0;
    int line = 0;
    while (pos < text.size()) {
        const std::size_t eol = text.find('\n', pos);
        const std::size_t stop = eol == std::string::npos ? text.size() : eol;
        const std::string_view raw = trim(std::string_view(text).substr(pos, stop - pos));
        pos = eol == std::string::npos ? text.size() : eol + 1;
        ++line;
        if (raw.empty()) {
            continue;
        }
        const std::size_t eq = raw.find('=');
        if (eq == std::string_view::npos) {
            throw LoadError(h.file + ": line " + std::to_string(line) +
                            " is not 'Key = Value': not a MetaImage header");
        }
        h.fields.emplace_back(trim(raw.substr(0, eq)), trim(raw.substr(eq + 1)));
        if (iequals(h.fields.back().first, "ElementDataFile")) {
            h.dataOffset = pos;
            return h;
        }
    }
    throw LoadError(h.file + ": no ElementDataFile line: not a MetaImage header");
}

struct Layout {
    VolumeFileHeader header;
    RawType rawType = RawType::Int16;
    bool bigEndian = false;
    bool compressed = false;
};

std::optional<RawType> elementType(std::string_view name) {
    static constexpr std::array<std::pair<std::string_view, RawType>, 8> table{{
        {"MET_UCHAR", RawType::UInt8},
        {"MET_CHAR", RawType::Int8},
        {"MET_SHORT", RawType::Int16},
        {"MET_USHORT", RawType::UInt16},
        {"MET_INT", RawType::Int32},
        {"MET_UINT", RawType::UInt32},
        {"MET_FLOAT", RawType::Float32},
        {"MET_DOUBLE", RawType::Float64},
    }};
    for (const auto& [key, type] : table) {
        if (iequals(key, name)) {
            return type;
        }
    }
    return std::nullopt;
}

Layout interpret(const MetaHeader& h) {
    Layout out;
    if (const auto* type = h.find({"ObjectType"}); type && !iequals(*type, "Image")) {
        h.fail("ObjectType", "'" + *type + "' is not an Image");
    }
    if (!h.find({"NDims"})) {
        h.fail("NDims", "missing");
    }
    const double nd = h.numbers({"NDims"}, 1, {})[0];
    if (nd != 2.0 && nd != 3.0) {
        h.fail("NDims", "only 2 or 3 dimensions are supported, found " + std::to_string(nd));
    }
    const auto n = static_cast<std::size_t>(nd);
    if (!h.find({"DimSize"})) {
        h.fail("DimSize", "missing");
    }
    const auto dims = h.numbers({"DimSize"}, n, {});
    const auto spacing = h.numbers({"ElementSpacing", "ElementSize"}, n, std::vector(n, 1.0));
    const auto offset = h.numbers({"Offset", "Position", "Origin"}, n, std::vector(n, 0.0));
    std::vector<double> identity(n * n, 0.0);
    for (std::size_t c = 0; c < n; ++c) {
        identity[c * n + c] = 1.0;
    }
    const auto matrix = h.numbers({"TransformMatrix", "Rotation", "Orientation"}, n * n, identity);

    VolumeGeometry& g = out.header.geometry;
    for (std::size_t c = 0; c < n; ++c) {
        if (dims[c] < 1.0 || dims[c] > 2147483647.0 || std::trunc(dims[c]) != dims[c]) {
            h.fail("DimSize", "sizes must be positive integers");
        }
        g.dims[static_cast<int>(c)] = static_cast<int>(dims[c]);
        g.spacing[static_cast<int>(c)] = spacing[c];
        g.origin[static_cast<int>(c)] = offset[c];
        // ITK writes the unit vector of axis c as numbers c*n .. c*n+n-1.
        for (std::size_t r = 0; r < n; ++r) {
            g.direction[static_cast<int>(c)][static_cast<int>(r)] = matrix[c * n + r];
        }
    }
    g = formats::checkedGeometry(g, h.file);

    if (const auto* channels = h.find({"ElementNumberOfChannels"}); channels && *channels != "1") {
        h.fail("ElementNumberOfChannels", "only single-channel images are supported");
    }
    const std::string* type = h.find({"ElementType"});
    if (!type) {
        h.fail("ElementType", "missing");
    }
    const auto raw = elementType(*type);
    if (!raw) {
        h.fail("ElementType", "unsupported element type '" + *type + "'");
    }
    out.rawType = *raw;
    out.header.voxelType = formats::volumeTypeFor(*raw);
    out.bigEndian = h.flag({"ElementByteOrderMSB", "BinaryDataByteOrderMSB"});
    out.compressed = h.flag({"CompressedData"});
    if (const auto* binary = h.find({"BinaryData"}); binary && !h.flag({"BinaryData"})) {
        h.fail("BinaryData", "ASCII voxel data are not supported");
    }
    if (const auto* modality = h.find({"Modality"})) {
        std::string m = *modality;
        if (m.starts_with("MET_MOD_")) {
            m = m.substr(8);
        }
        out.header.modality = (m == "UNKNOWN") ? "" : (m == "OTHER" ? "OT" : m);
    }
    if (const auto* d = h.find({"SeriesDescription", "Comment"})) {
        out.header.description = *d;
    }
    if (dims.size() == 2) {
        out.header.warnings.push_back("2D MetaImage read as a volume of depth 1");
    }
    return out;
}

} // namespace

VolumeFileHeader readMetaImageHeader(const fs::path& mhd) {
    return interpret(parseHeader(mhd)).header;
}

namespace {

// Where a MetaImage's voxels are: the data file, open at their first byte.
struct DataFile {
    MetaHeader h;
    Layout layout;
    fs::path path;
    std::uint64_t start = 0;
    std::uint64_t available = 0;
    std::ifstream in;
};

void openData(const fs::path& mhd, DataFile& f) {
    f.h = parseHeader(mhd);
    f.layout = interpret(f.h);
    const MetaHeader& h = f.h;
    const Layout& layout = f.layout;
    const std::string& dataName = *h.find({"ElementDataFile"});
    const bool local = iequals(dataName, "LOCAL");
    if (iequals(dataName, "LIST") || dataName.find('%') != std::string::npos) {
        h.fail("ElementDataFile", "lists of data files are not supported");
    }
    const fs::path dataPath = local ? mhd : (mhd.parent_path() / fs::path(dataName));
    std::error_code ec;
    const std::uint64_t fileSize = fs::file_size(dataPath, ec);
    if (ec) {
        throw LoadError(h.file + ": data file " + dataPath.string() + " cannot be read (" +
                        ec.message() + ")");
    }
    const std::uint64_t expected =
        layout.header.geometry.voxelCount() * formats::rawTypeSize(layout.rawType);
    std::uint64_t start = local ? h.dataOffset : 0;
    if (const auto* hs = h.find({"HeaderSize"}); hs && !local) {
        const double skip = h.numbers({"HeaderSize"}, 1, {})[0];
        if (skip == -1.0 && !layout.compressed) {
            start = fileSize >= expected ? fileSize - expected : 0;
        } else if (skip >= 0.0 && skip <= static_cast<double>(fileSize)) {
            start = static_cast<std::uint64_t>(skip);
        } else {
            h.fail("HeaderSize", "must be -1 or a byte count within the data file");
        }
    }
    const std::uint64_t available = fileSize > start ? fileSize - start : 0;
    if (!layout.compressed && available < expected) {
        throw LoadError(h.file + ": data file " + dataPath.string() + " is truncated: expected " +
                        std::to_string(expected) + " bytes of voxel data, found " +
                        std::to_string(available));
    }
    // Deflate expands at most 1032 to 1: less data than that cannot hold the
    // volume, which is refused before it is allocated (fuzz_metaimage: 11 GB
    // for a header of a few hundred bytes).
    constexpr std::uint64_t kMaxInflateRatio = 1032;
    if (layout.compressed && available < (expected + kMaxInflateRatio - 1) / kMaxInflateRatio) {
        throw LoadError(h.file + ": CompressedData: " + std::to_string(available) +
                        " bytes of zlib data in " + dataPath.string() + " cannot inflate to the " +
                        std::to_string(expected) + " bytes that DimSize and ElementType need");
    }
    f.in.open(dataPath, std::ios::binary);
    f.in.seekg(static_cast<std::streamoff>(start));
    if (!f.in) {
        throw LoadError(h.file + ": cannot open data file " + dataPath.string());
    }
    f.path = dataPath;
    f.start = start;
    f.available = available;
}

} // namespace

bool metaImageHasSliceRanges(const fs::path& mhd) {
    return !interpret(parseHeader(mhd)).compressed;
}

Volume readMetaImageSlices(const fs::path& mhd, int k0, int k1) {
    DataFile f;
    openData(mhd, f);
    const VolumeGeometry& g = f.layout.header.geometry;
    if (f.layout.compressed) {
        throw LoadError(f.h.file + ": compressed voxels have no byte range per slice");
    }
    if (k0 < 0 || k1 > g.dims.z || k0 >= k1) {
        throw LoadError(f.h.file + ": slices " + std::to_string(k0) + " .. " +
                        std::to_string(k1 - 1) + " are not within its " + std::to_string(g.dims.z));
    }
    const std::uint64_t sliceBytes =
        std::uint64_t(g.dims.x) * std::uint64_t(g.dims.y) * formats::rawTypeSize(f.layout.rawType);
    f.in.seekg(static_cast<std::streamoff>(f.start + sliceBytes * std::uint64_t(k0)));
    VolumeGeometry slab = g;
    slab.dims.z = k1 - k0;
    slab.origin = g.toPatient(glm::dvec3(0.0, 0.0, double(k0)));
    Volume volume = formats::allocateVolume(slab, f.layout.header.voxelType, f.h.file);
    const std::string label = f.h.file + " (data file " + f.path.filename().string() + ")";
    formats::readVoxels(
        [&](std::span<std::byte> b) {
            f.in.read(reinterpret_cast<char*>(b.data()), static_cast<std::streamsize>(b.size()));
            return static_cast<std::size_t>(f.in.gcount());
        },
        f.layout.rawType, f.layout.bigEndian, {}, volume, label);
    volume.modality = f.layout.header.modality;
    volume.description = f.layout.header.description;
    volume.warnings = f.layout.header.warnings;
    return volume;
}

Volume readMetaImage(const fs::path& mhd) {
    DataFile f;
    openData(mhd, f);
    const MetaHeader& h = f.h;
    const Layout& layout = f.layout;
    std::ifstream& in = f.in;
    const std::uint64_t available = f.available;
    const fs::path& dataPath = f.path;
    Volume volume =
        formats::allocateVolume(layout.header.geometry, layout.header.voxelType, h.file);
    const std::string label = h.file + " (data file " + dataPath.filename().string() + ")";
    if (layout.compressed) {
        std::uint64_t compressedBytes = available;
        if (h.find({"CompressedDataSize"})) {
            const double stated = h.numbers({"CompressedDataSize"}, 1, {})[0];
            if (stated < 0.0) {
                h.fail("CompressedDataSize", "must not be negative");
            }
            compressedBytes = static_cast<std::uint64_t>(
                std::min(static_cast<double>(available), std::floor(stated)));
        }
        formats::InflateReader source(
            [&in, left = compressedBytes](std::span<std::byte> b) mutable {
                const auto n =
                    static_cast<std::streamsize>(std::min<std::uint64_t>(left, b.size()));
                in.read(reinterpret_cast<char*>(b.data()), n);
                const auto got = static_cast<std::size_t>(in.gcount());
                left -= got;
                return got;
            },
            label);
        formats::readVoxels([&](std::span<std::byte> b) { return source.read(b); }, layout.rawType,
                            layout.bigEndian, {}, volume, label);
    } else {
        formats::readVoxels(
            [&](std::span<std::byte> b) {
                in.read(reinterpret_cast<char*>(b.data()), static_cast<std::streamsize>(b.size()));
                return static_cast<std::size_t>(in.gcount());
            },
            layout.rawType, layout.bigEndian, {}, volume, label);
    }
    volume.modality = layout.header.modality;
    volume.description = layout.header.description;
    volume.warnings = layout.header.warnings;
    return volume;
}

} // namespace lucent
