#include "core/formats/MetaImage.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/formats/AtomicFile.h"

namespace lucent {

namespace fs = std::filesystem;

namespace {

std::string anatomicalOrientation(const glm::dmat3& d) {
    std::string code;
    for (int c = 0; c < 3; ++c) {
        const glm::dvec3 v = d[c];
        int axis = 0;
        for (int r = 1; r < 3; ++r) {
            if (std::abs(v[r]) > std::abs(v[axis])) {
                axis = r;
            }
        }
        static constexpr char from[3][2] = {{'R', 'L'}, {'A', 'P'}, {'I', 'S'}};
        code += from[axis][v[axis] < 0 ? 1 : 0];
    }
    return code;
}

std::string formatNumbers(std::initializer_list<double> values) {
    std::string out;
    for (const double x : values) {
        std::array<char, 32> buf{};
        const auto [end, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), x);
        (void)ec;
        if (!out.empty()) {
            out += ' ';
        }
        out.append(buf.data(), end);
    }
    return out;
}

std::string singleLine(std::string s) {
    std::replace_if(
        s.begin(), s.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    return s;
}

} // namespace

void writeMetaImage(const Volume& v, const fs::path& mhd) {
    if (v.empty()) {
        throw std::runtime_error(mhd.string() + ": cannot write an empty volume");
    }
    const fs::path raw = mhd.parent_path() / (mhd.stem().string() + ".raw");
    formats::AtomicFileWriter rawOut(raw);
    const auto bytes = v.bytes();
    if constexpr (std::endian::native == std::endian::little) {
        rawOut.stream().write(reinterpret_cast<const char*>(bytes.data()),
                              static_cast<std::streamsize>(bytes.size()));
    } else {
        const std::size_t n = voxelSize(v.type());
        std::vector<char> element(n);
        for (std::size_t i = 0; i < bytes.size(); i += n) {
            std::reverse_copy(reinterpret_cast<const char*>(bytes.data()) + i,
                              reinterpret_cast<const char*>(bytes.data()) + i + n, element.begin());
            rawOut.stream().write(element.data(), static_cast<std::streamsize>(n));
        }
    }
    rawOut.finish();

    const VolumeGeometry& g = v.geometry();
    const glm::dmat3& d = g.direction;
    const char* type = v.type() == VoxelType::Int16    ? "MET_SHORT"
                       : v.type() == VoxelType::UInt16 ? "MET_USHORT"
                                                       : "MET_FLOAT";
    formats::AtomicFileWriter header(mhd);
    std::ostream& os = header.stream();
    os << "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
       << "CompressedData = False\n"
       << "TransformMatrix = "
       << formatNumbers(
              {d[0][0], d[0][1], d[0][2], d[1][0], d[1][1], d[1][2], d[2][0], d[2][1], d[2][2]})
       << "\nOffset = " << formatNumbers({g.origin.x, g.origin.y, g.origin.z})
       << "\nCenterOfRotation = 0 0 0\nAnatomicalOrientation = " << anatomicalOrientation(d)
       << "\nElementSpacing = " << formatNumbers({g.spacing.x, g.spacing.y, g.spacing.z})
       << "\nDimSize = " << g.dims.x << ' ' << g.dims.y << ' ' << g.dims.z << '\n';
    if (!v.modality.empty()) {
        static constexpr std::array<std::string_view, 4> known{"CT", "MR", "NM", "US"};
        const bool isKnown = std::find(known.begin(), known.end(), v.modality) != known.end();
        os << "Modality = " << (isKnown ? "MET_MOD_" : "") << singleLine(v.modality) << '\n';
    }
    if (!v.description.empty()) {
        os << "SeriesDescription = " << singleLine(v.description) << '\n';
    }
    os << "ElementType = " << type << "\nElementDataFile = " << raw.filename().string() << '\n';
    header.finish();
    rawOut.commit();
    header.commit();
}

} // namespace lucent
