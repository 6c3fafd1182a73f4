#include "core/formats/InVesaliusProject.h"

#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "core/formats/Plist.h"
#include "core/formats/RawVoxels.h"
#include "core/formats/TarGzReader.h"
#include "core/io/LoadControl.h"

namespace lucent {

namespace fs = std::filesystem;
using formats::PlistValue;
using formats::RawType;

namespace {

constexpr std::uint64_t maxPlistBytes = std::uint64_t{16} << 20;

std::string_view baseName(std::string_view path) {
    const std::size_t slash = path.rfind('/');
    return slash == std::string_view::npos ? path : path.substr(slash + 1);
}

struct Project {
    VolumeFileHeader header;
    std::string matrixEntry; // path of the matrix file inside the archive
    RawType rawType = RawType::Int16;
};

class Keys {
public:
    Keys(std::string file) : file_(std::move(file)) {}

    const PlistValue& get(const PlistValue& dict, std::string_view key,
                          std::string_view where) const {
        const PlistValue* v = dict.find(key);
        if (!v) {
            fail(where, key, "missing");
        }
        return *v;
    }
    std::string string(const PlistValue& dict, std::string_view key, std::string_view where) const {
        const PlistValue& v = get(dict, key, where);
        if (v.kind != PlistValue::Kind::String) {
            fail(where, key, "is not a string");
        }
        return v.text;
    }
    std::array<double, 3> triple(const PlistValue& dict, std::string_view key,
                                 std::string_view where) const {
        const PlistValue& v = get(dict, key, where);
        if (v.kind != PlistValue::Kind::Array || v.items.size() != 3) {
            fail(where, key, "is not an array of 3 numbers");
        }
        std::array<double, 3> out{};
        for (std::size_t i = 0; i < 3; ++i) {
            char* end = nullptr;
            const std::string& text = v.items[i].text;
            out[i] = std::strtod(text.c_str(), &end);
            if (!v.items[i].isNumber() || text.empty() || *end != '\0' || !std::isfinite(out[i])) {
                fail(where, key, "is not an array of 3 numbers");
            }
        }
        return out;
    }
    [[noreturn]] void fail(std::string_view where, std::string_view key,
                           std::string_view what) const {
        throw LoadError(file_ + ": main.plist: key '" + std::string(where) + std::string(key) +
                        "' " + std::string(what));
    }

private:
    std::string file_;
};

std::optional<RawType> dtypeOf(std::string_view dtype) {
    static constexpr std::array<std::pair<std::string_view, RawType>, 8> table{{
        {"int16", RawType::Int16},
        {"uint16", RawType::UInt16},
        {"float32", RawType::Float32},
        {"uint8", RawType::UInt8},
        {"int8", RawType::Int8},
        {"int32", RawType::Int32},
        {"uint32", RawType::UInt32},
        {"float64", RawType::Float64},
    }};
    for (const auto& [name, type] : table) {
        if (name == dtype) {
            return type;
        }
    }
    return std::nullopt;
}

Project interpret(const PlistValue& root, const std::string& dir, const std::string& file) {
    const Keys keys(file);
    if (root.kind != PlistValue::Kind::Dict) {
        throw LoadError(file + ": main.plist: top level is not a dict");
    }
    Project p;
    const PlistValue& matrix = keys.get(root, "matrix", "");
    const std::string dtype = keys.string(matrix, "dtype", "matrix.");
    const auto raw = dtypeOf(dtype);
    if (!raw) {
        keys.fail("matrix.", "dtype", "names an unsupported type '" + dtype + "'");
    }
    p.rawType = *raw;
    const std::string name = keys.string(matrix, "filename", "matrix.");
    if (name.empty() || name.find('/') != std::string::npos || name == "..") {
        keys.fail("matrix.", "filename", "is not a plain file name");
    }
    p.matrixEntry = dir + name;
    const auto shape = keys.triple(matrix, "shape", "matrix.");
    const auto spacing = keys.triple(root, "spacing", "");

    VolumeGeometry& g = p.header.geometry;
    for (int a = 0; a < 3; ++a) {
        const double n = shape[static_cast<std::size_t>(2 - a)]; // shape is (slices, rows, cols)
        if (n < 1.0 || n > 1e6 || std::trunc(n) != n) {
            keys.fail("matrix.", "shape", "must hold positive integers");
        }
        g.dims[a] = static_cast<int>(n);
        g.spacing[a] = spacing[static_cast<std::size_t>(a)];
    }
    // Columns run right -> left, rows posterior -> anterior, slices inferior -> superior.
    g.direction = glm::dmat3(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 1.0);
    const glm::dvec3 halfExtent = g.spacing * (glm::dvec3(g.dims) - 1.0) * 0.5;
    g.origin = -(g.direction * halfExtent);
    g = formats::checkedGeometry(g, file);
    p.header.voxelType = formats::volumeTypeFor(p.rawType);
    if (const PlistValue* m = root.find("modality"); m && m->kind == PlistValue::Kind::String) {
        p.header.modality = m->text;
    }
    if (const PlistValue* n = root.find("name"); n && n->kind == PlistValue::Kind::String) {
        p.header.description = n->text;
    }
    p.header.warnings.push_back("InVesalius projects hold no patient coordinates: orientation "
                                "follows InVesalius' convention, centred on the volume");
    return p;
}

Project readProject(const fs::path& inv3) {
    const std::string file = inv3.string();
    formats::TarGzReader tar(inv3);
    while (const auto entry = tar.next()) {
        if (baseName(entry->name) != "main.plist") {
            continue;
        }
        if (entry->size > maxPlistBytes) {
            throw LoadError(file + ": main.plist is implausibly large");
        }
        std::string xml(static_cast<std::size_t>(entry->size), '\0');
        if (tar.read(std::as_writable_bytes(std::span(xml))) != xml.size()) {
            throw LoadError(file + ": main.plist is truncated");
        }
        PlistValue root;
        try {
            root = formats::parsePlist(xml);
        } catch (const std::runtime_error& e) {
            throw LoadError(file + ": main.plist: " + e.what());
        }
        const std::string dir =
            entry->name.substr(0, entry->name.size() - baseName(entry->name).size());
        return interpret(root, dir, file);
    }
    throw LoadError(file + ": no main.plist inside: not an InVesalius 3 project");
}

} // namespace

VolumeFileHeader readInVesaliusHeader(const fs::path& inv3) {
    return readProject(inv3).header;
}

Volume readInVesalius(const fs::path& inv3) {
    const Project p = readProject(inv3);
    const std::string file = inv3.string();
    formats::TarGzReader tar(inv3);
    const std::uint64_t expected = p.header.geometry.voxelCount() * formats::rawTypeSize(p.rawType);
    while (const auto entry = tar.next()) {
        if (entry->name != p.matrixEntry) {
            continue;
        }
        if (entry->size < expected) {
            throw LoadError(file + ": " + p.matrixEntry + " is truncated: expected " +
                            std::to_string(expected) + " bytes, found " +
                            std::to_string(entry->size));
        }
        Volume volume = formats::allocateVolume(p.header.geometry, p.header.voxelType, file);
        formats::readVoxels([&tar](std::span<std::byte> b) { return tar.read(b); }, p.rawType,
                            false, {}, volume, file + ": " + p.matrixEntry);
        volume.modality = p.header.modality;
        volume.description = p.header.description;
        volume.warnings = p.header.warnings;
        return volume;
    }
    throw LoadError(file + ": the image matrix " + p.matrixEntry + " is missing from the project");
}

} // namespace lucent
