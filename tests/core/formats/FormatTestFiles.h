#pragma once

// Helpers for test_volume_formats: files written byte by byte, as other tools would.

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <zlib.h>

#include <QString>
#include <QTemporaryDir>

#include <glm/gtc/matrix_transform.hpp>

#include "core/io/LoadControl.h"
#include "core/volume/Volume.h"

namespace lucent::test {

inline void writeBytes(const std::filesystem::path& path, const void* data, std::size_t size) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}

inline void writeText(const std::filesystem::path& path, const std::string& text) {
    writeBytes(path, text.data(), text.size());
}

inline void writeGz(const std::filesystem::path& path, const void* data, std::size_t size) {
    gzFile f = gzopen(path.string().c_str(), "wb");
    gzwrite(f, data, static_cast<unsigned>(size));
    gzclose(f);
}

// A little-endian NIfTI-1 header with every field the readers look at.
struct NiftiHeader {
    std::array<std::uint8_t, 348> bytes{};

    bool bigEndian = false;

    NiftiHeader(std::array<short, 3> dims, short datatype, short bitpix, bool big = false)
        : bigEndian(big) {
        put<int>(0, 348);
        put<short>(40, 3);
        for (int i = 0; i < 3; ++i) {
            put<short>(42 + 2 * i, dims[static_cast<std::size_t>(i)]);
        }
        put<short>(48, 1);
        put<short>(70, datatype);
        put<short>(72, bitpix);
        put<float>(76, 1.0f); // pixdim[0] (qfac)
        for (int i = 1; i < 4; ++i) {
            put<float>(76 + 4 * i, 1.0f);
        }
        put<float>(108, 352.0f); // vox_offset
        std::memcpy(bytes.data() + 344, "n+1\0", 4);
    }
    template <class T> void put(std::size_t offset, T v) {
        std::memcpy(bytes.data() + offset, &v, sizeof v);
        if (bigEndian) {
            std::reverse(bytes.begin() + static_cast<long>(offset),
                         bytes.begin() + static_cast<long>(offset + sizeof v));
        }
    }
    void setSform(const std::array<std::array<float, 4>, 3>& rows) {
        put<short>(254, 1);
        for (std::size_t r = 0; r < 3; ++r) {
            for (std::size_t c = 0; c < 4; ++c) {
                put<float>(280 + 16 * r + 4 * c, rows[r][c]);
            }
        }
    }
    // Header, 4 bytes of extension flags, then the voxels.
    std::vector<std::uint8_t> file(const void* voxels, std::size_t size) const {
        std::vector<std::uint8_t> out(bytes.begin(), bytes.end());
        out.resize(352, 0);
        if (size > 0) {
            const auto* v = static_cast<const std::uint8_t*>(voxels);
            out.insert(out.end(), v, v + size);
        }
        return out;
    }
};

// One member of a tar archive: type '0' a file, '5' a directory, '2' a symlink
// (data: its target), 'L' a GNU long name for the next member, 'x' a pax header.
struct TarMember {
    std::string name;
    std::string data;
    char type = '0';
};

// The bytes of a tar with ustar headers, as Python's tarfile writes them.
inline std::string tarBytes(const std::vector<TarMember>& members) {
    std::string tar;
    for (const auto& [name, data, type] : members) {
        const bool link = type == '2';
        const std::size_t size = link ? 0 : data.size();
        std::array<char, 512> h{};
        std::memcpy(h.data(), name.data(), std::min<std::size_t>(name.size(), 99));
        std::snprintf(h.data() + 100, 8, "%07o", type == '5' ? 0755 : 0644);
        std::snprintf(h.data() + 108, 8, "%07o", 0);
        std::snprintf(h.data() + 116, 8, "%07o", 0);
        std::snprintf(h.data() + 124, 12, "%011lo", static_cast<unsigned long>(size));
        std::snprintf(h.data() + 136, 12, "%011o", 0);
        h[156] = type;
        if (link) {
            std::memcpy(h.data() + 157, data.data(), std::min<std::size_t>(data.size(), 99));
        }
        std::memcpy(h.data() + 257, "ustar", 6);
        std::memcpy(h.data() + 263, "00", 2);
        std::memset(h.data() + 148, ' ', 8);
        unsigned sum = 0;
        for (const char c : h) {
            sum += static_cast<unsigned char>(c);
        }
        std::snprintf(h.data() + 148, 8, "%06o", sum);
        tar.append(h.data(), h.size());
        if (!link) {
            tar += data;
            tar.append((512 - data.size() % 512) % 512, '\0');
        }
    }
    tar.append(1024, '\0');
    return tar;
}

inline void writeTarMembers(const std::filesystem::path& path,
                            const std::vector<TarMember>& members) {
    const std::string tar = tarBytes(members);
    writeGz(path, tar.data(), tar.size());
}

inline void writeTarGz(const std::filesystem::path& path,
                       const std::vector<std::pair<std::string, std::string>>& entries) {
    std::vector<TarMember> members;
    for (const auto& [name, data] : entries) {
        members.push_back({name, data, '0'});
    }
    writeTarMembers(path, members);
}

inline std::filesystem::path dirOf(const QTemporaryDir& dir) {
    return std::filesystem::path(dir.path().toStdString());
}

// The LoadError message of f, or "" when it did not throw one.
inline QString loadErrorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const LoadError& e) {
        return QString::fromStdString(e.what());
    }
    return {};
}

inline bool near(const glm::dvec3& a, const glm::dvec3& b, double tol) {
    return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::dvec3(tol)));
}

inline VolumeGeometry obliqueGeometry() {
    VolumeGeometry g;
    g.dims = {7, 5, 3};
    g.spacing = {0.7, 1.3, 2.5};
    g.origin = {-12.5, 33.25, 101.0};
    g.direction =
        glm::dmat3(glm::rotate(glm::dmat4(1.0), 0.4, glm::normalize(glm::dvec3(1, 2, 3))));
    return g;
}

template <class T> T pattern(int i, int j, int k) {
    if constexpr (std::is_same_v<T, float>) {
        return static_cast<float>(i * 0.25 - j * 3.5 + k * 1000.125);
    } else if constexpr (std::is_same_v<T, std::uint16_t>) {
        return static_cast<T>(60000 + i + 10 * j + 100 * k);
    } else {
        return static_cast<T>(-1024 + i + 10 * j + 100 * k);
    }
}

template <class T> Volume patternVolume(const VolumeGeometry& g) {
    Volume v(g, VoxelTypeOf<T>::value);
    auto voxels = v.voxels<T>();
    for (int k = 0; k < g.dims.z; ++k) {
        for (int j = 0; j < g.dims.y; ++j) {
            for (int i = 0; i < g.dims.x; ++i) {
                voxels[v.linearIndex(i, j, k)] = pattern<T>(i, j, k);
            }
        }
    }
    return v;
}

template <class T> bool matchesPattern(const Volume& v) {
    const auto voxels = v.voxels<T>();
    for (int k = 0; k < v.dims().z; ++k) {
        for (int j = 0; j < v.dims().y; ++j) {
            for (int i = 0; i < v.dims().x; ++i) {
                if (voxels[v.linearIndex(i, j, k)] != pattern<T>(i, j, k)) {
                    return false;
                }
            }
        }
    }
    return true;
}

inline bool sameGeometry(const VolumeGeometry& a, const VolumeGeometry& b) {
    return a.dims == b.dims && a.spacing == b.spacing && a.origin == b.origin &&
           a.direction == b.direction;
}

inline std::string bigEndianShorts(const std::vector<std::int16_t>& values) {
    std::string out;
    for (const auto v : values) {
        const auto u = static_cast<std::uint16_t>(v);
        out += static_cast<char>(u >> 8);
        out += static_cast<char>(u & 0xff);
    }
    return out;
}

// The corners of a volume's box in patient coordinates: lowest and highest x, y, z.
inline std::pair<glm::dvec3, glm::dvec3> patientBounds(const VolumeGeometry& g) {
    const glm::dvec3 a = g.toPatient({0, 0, 0});
    const glm::dvec3 b = g.toPatient(glm::dvec3(g.dims - 1));
    return {glm::min(a, b), glm::max(a, b)};
}

struct AxialCounts {
    int tissue = 0;        // above -300 HU
    int anteriorBone = 0;  // above 1200 HU (teeth, dense cortical bone), y below the centre
    int posteriorBone = 0; // the same, y above the centre
};

// Samples the LPS axial plane at height z on a 1 mm grid (nearest voxel).
inline AxialCounts axialPlaneCounts(const Volume& v, double z) {
    const VolumeGeometry& g = v.geometry();
    const auto [lower, upper] = patientBounds(g);
    const double centreY = (lower.y + upper.y) * 0.5;
    const glm::dmat4 toIndex = g.patientToIndex();
    AxialCounts c;
    for (double y = lower.y; y <= upper.y; y += 1.0) {
        for (double x = lower.x; x <= upper.x; x += 1.0) {
            const glm::ivec3 ijk(glm::round(glm::dvec3(toIndex * glm::dvec4(x, y, z, 1.0))));
            if (glm::any(glm::lessThan(ijk, glm::ivec3(0))) ||
                glm::any(glm::greaterThanEqual(ijk, g.dims))) {
                continue;
            }
            const double hu = v.value(ijk.x, ijk.y, ijk.z);
            c.tissue += hu > -300.0;
            if (hu > 1200.0) {
                (y < centreY ? c.anteriorBone : c.posteriorBone) += 1;
            }
        }
    }
    return c;
}

} // namespace lucent::test
