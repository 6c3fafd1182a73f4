#include "core/surface/FlyingEdges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "core/surface/MarchingCubesTable.h"

namespace lucent {

namespace {

// inside = value >= iso, compared in the voxel's own arithmetic: an integer
// threshold ceil(iso) for integer voxels, the smallest float >= iso for floats
// (NaN voxels are outside).
template <class T> class InsideTest {
public:
    explicit InsideTest(double iso) {
        if constexpr (std::is_integral_v<T>) {
            const double limit = 1e9; // far beyond any 16-bit value
            threshold_ = static_cast<int>(std::clamp(std::ceil(iso), -limit, limit));
        } else {
            const double big = std::numeric_limits<float>::max();
            float f = iso > big    ? std::numeric_limits<float>::infinity()
                      : iso < -big ? -big
                                   : static_cast<float>(iso);
            if (static_cast<double>(f) < iso) {
                f = std::nextafter(f, std::numeric_limits<float>::infinity());
            }
            threshold_ = f;
        }
    }
    unsigned operator()(T v) const { return v >= threshold_ ? 1u : 0u; }

private:
    std::conditional_t<std::is_integral_v<T>, int, float> threshold_{};
};

// Counts and output places of one row of the block grown by the outside layer
// (padded indices: q = j + 1, s = k + 1, x-edge e joins padded voxels e, e + 1).
struct RowState {
    std::int32_t first = std::numeric_limits<std::int32_t>::max(); // first x-edge crossing
    std::int32_t last = -1;                                        // last x-edge crossing
    std::uint32_t xCount = 0;    // crossings on this row's x-edges
    std::uint32_t yCount = 0;    // ... on the y-edges to row q + 1
    std::uint32_t zCount = 0;    // ... on the z-edges to row s + 1
    std::uint32_t triangles = 0; // in the cells between rows q, q + 1 and s, s + 1
    std::int32_t cellFirst = 0;  // those cells lie in [cellFirst, cellLast]
    std::int32_t cellLast = -1;
    std::uint64_t vertexOffset = 0; // x, then y, then z vertices
    std::uint64_t triangleOffset = 0;
};

// 1 when corners a and b of a cube case lie on different sides.
constexpr unsigned cut(unsigned cube, int a, int b) {
    return (cube >> a ^ cube >> b) & 1u;
}

// Walking along a row of cells: the id of the next vertex on each family of
// edges the cells touch (x-edges of the four rows around them, y-edges of
// rows (q, s) and (q, s + 1), z-edges of rows (q, s) and (q + 1, s)).
struct EdgeIds {
    std::uint32_t x00, x10, x01, x11, y00, y01, z00, z10;

    // Ids of the 12 edges of a cell, numbered as in MarchingCubesTable.h
    // (meaningful for the edges the case cuts).
    std::array<std::uint32_t, 12> ofCell(unsigned cube) const {
        return {x00, x10,
                x01, x11,
                y00, y00 + cut(cube, 0, 2),
                y01, y01 + cut(cube, 4, 6),
                z00, z00 + cut(cube, 0, 4),
                z10, z10 + cut(cube, 2, 6)};
    }
    void pass(unsigned cube) {
        x00 += cut(cube, 0, 1);
        x10 += cut(cube, 2, 3);
        x01 += cut(cube, 4, 5);
        x11 += cut(cube, 6, 7);
        y00 += cut(cube, 0, 2);
        y01 += cut(cube, 4, 6);
        z00 += cut(cube, 0, 4);
        z10 += cut(cube, 2, 6);
    }
};

template <class T> class FlyingEdges {
public:
    FlyingEdges(const VoxelBlock<T>& block, const ContourSettings& settings)
        : block_(block), settings_(settings), inside_(settings.iso), n_(block.size),
          cases_(static_cast<std::size_t>(n_.x + 1) * n_.y * n_.z),
          zeros_(static_cast<std::size_t>(n_.x + 1), 0),
          rows_(static_cast<std::size_t>(n_.y + 2) * (n_.z + 2)), linear_(settings.blockToPatient),
          offset_(settings.blockToPatient[3]) {}

    bool run(TriangleMesh& out) {
        const double from = settings_.progressFrom;
        const double span = settings_.progressTo - from;
        const auto& progress = settings_.progress;
        bool ok = parallelChunks(n_.z, from, from + 0.35 * span, progress, [this](int k) {
            for (int j = 0; j < n_.y; ++j) {
                classifyRow(j, k);
            }
        });
        ok = ok && parallelChunks(n_.z + 1, from + 0.35 * span, from + 0.6 * span, progress,
                                  [this](int s) {
                                      for (int q = 0; q <= n_.y; ++q) {
                                          countCellRow(q, s);
                                      }
                                  });
        if (ok) {
            allocate(out);
            ok = parallelChunks(n_.z + 1, from + 0.6 * span, from + span, progress,
                                [this, &out](int s) {
                                    for (int q = 0; q <= n_.y; ++q) {
                                        writeCellRow(q, s, out);
                                    }
                                });
        }
        if (!ok) {
            out = TriangleMesh{};
        }
        return ok;
    }

private:
    std::size_t rowIndex(int q, int s) const {
        return static_cast<std::size_t>(q) + static_cast<std::size_t>(n_.y + 2) * s;
    }
    bool inBlock(int q, int s) const { return q >= 1 && q <= n_.y && s >= 1 && s <= n_.z; }
    // Where the x-edge cases of block row (j, k) start.
    std::size_t caseOffset(int j, int k) const {
        return (static_cast<std::size_t>(j) + static_cast<std::size_t>(n_.y) * k) * (n_.x + 1);
    }
    const std::uint8_t* edgeCases(int q, int s) const {
        return inBlock(q, s) ? cases_.data() + caseOffset(q - 1, s - 1) : zeros_.data();
    }
    const T* voxels(int q, int s) const {
        return inBlock(q, s) ? block_.row(q - 1, s - 1) : nullptr;
    }

    // Pass 1: edge case (bit 0: left voxel inside, bit 1: right voxel inside)
    // of each x-edge of block row (j, k), outside layer included.
    void classifyRow(int j, int k) {
        const T* v = block_.row(j, k);
        std::uint8_t* ec = cases_.data() + caseOffset(j, k);
        // A local bound (the byte stores could alias a member) and no carried
        // dependency, so that both loops vectorise.
        const int n = n_.x;
        const InsideTest<T> inside = inside_;
        ec[0] = static_cast<std::uint8_t>(inside(v[0]) << 1);
        for (int i = 1; i < n; ++i) {
            ec[i] = static_cast<std::uint8_t>(inside(v[i - 1]) | inside(v[i]) << 1);
        }
        ec[n] = static_cast<std::uint8_t>(inside(v[n - 1]));
        std::uint32_t count = 0;
        for (int e = 0; e <= n; ++e) {
            count += (ec[e] ^ (ec[e] >> 1)) & 1u;
        }
        RowState& row = rows_[rowIndex(j + 1, k + 1)];
        row.xCount = count;
        if (count > 0) {
            int e = 0;
            while (((ec[e] ^ (ec[e] >> 1)) & 1u) == 0) {
                ++e;
            }
            row.first = e;
            e = n;
            while (((ec[e] ^ (ec[e] >> 1)) & 1u) == 0) {
                --e;
            }
            row.last = e;
        }
    }

    // The cube case of cell c between rows (q, s), (q+1, s), (q, s+1), (q+1, s+1).
    static unsigned cubeCase(const std::uint8_t* const ec[4], int c) {
        return ec[0][c] | ec[1][c] << 2 | ec[2][c] << 4 | ec[3][c] << 6;
    }

    // Whether cells c .. c + 7 are all outside or all inside (eight bytes of
    // each row at once): a run of such cells has no crossing, so the cell
    // loops skip it.
    static bool uncut(const std::uint8_t* const ec[4], int c) {
        std::uint64_t row[4];
        for (int r = 0; r < 4; ++r) {
            std::memcpy(&row[r], ec[r] + c, sizeof(std::uint64_t));
        }
        const std::uint64_t any = row[0] | row[1] | row[2] | row[3];
        const std::uint64_t all = row[0] & row[1] & row[2] & row[3];
        return any == 0 || all == 0x0303030303030303u;
    }

    // Pass 2. Every voxel left of the first crossing of a row is outside, like
    // the outside layer it starts with (and likewise right of the last), so
    // only cells within the union of the four rows' crossing ranges can be cut.
    void countCellRow(int q, int s) {
        RowState& row = rows_[rowIndex(q, s)];
        const RowState* around[4] = {&row, &rows_[rowIndex(q + 1, s)], &rows_[rowIndex(q, s + 1)],
                                     &rows_[rowIndex(q + 1, s + 1)]};
        int first = around[0]->first, last = around[0]->last;
        for (const RowState* r : around) {
            first = std::min(first, r->first);
            last = std::max(last, r->last);
        }
        if (first > last) {
            return;
        }
        const std::uint8_t* const ec[4] = {edgeCases(q, s), edgeCases(q + 1, s),
                                           edgeCases(q, s + 1), edgeCases(q + 1, s + 1)};
        const auto& table = marchingCubesCases();
        std::uint32_t triangles = 0, y = 0, z = 0;
        for (int c = first; c <= last;) {
            if (c + 8 <= last + 1 && uncut(ec, c)) {
                c += 8;
                continue;
            }
            const unsigned cube = cubeCase(ec, c++);
            triangles += table[cube].triangleCount;
            y += cut(cube, 0, 2); // the y- and z-edges at the cell's left corner
            z += cut(cube, 0, 4);
        }
        const unsigned cube = cubeCase(ec, last);
        y += cut(cube, 1, 3); // and at the right corner of the last cell
        z += cut(cube, 1, 5);
        row.triangles = triangles;
        row.yCount = y;
        row.zCount = z;
        row.cellFirst = first;
        row.cellLast = last;
    }

    // Pass 3: every row's first vertex and triangle, in row order.
    void allocate(TriangleMesh& out) {
        std::uint64_t vertices = 0, triangles = 0;
        for (RowState& row : rows_) {
            row.vertexOffset = vertices;
            row.triangleOffset = triangles;
            vertices += row.xCount + row.yCount + row.zCount;
            triangles += row.triangles;
        }
        if (vertices > std::numeric_limits<std::uint32_t>::max()) {
            throw std::length_error("isosurface: " + std::to_string(vertices) +
                                    " vertices do not fit 32-bit indices");
        }
        out.vertices.resize(vertices);
        out.triangles.resize(triangles);
    }

    double crossing(double a, double b) const {
        double t = (settings_.iso - a) / (b - a);
        t = t > kMinEdgeFraction ? t : kMinEdgeFraction; // NaN lands here too
        return t < 1.0 - kMinEdgeFraction ? t : 1.0 - kMinEdgeFraction;
    }
    glm::dvec3 toPatient(double i, double j, double k) const {
        return offset_ + linear_ * glm::dvec3(i, j, k);
    }
    // The vertex on x-edge c of row (q, s); on the y-edge (or z-edge) at padded
    // voxel p between rows (q, s) and (q + 1, s) (or (q, s + 1)).
    glm::dvec3 xVertex(const T* v, int c, int q, int s) const {
        const double t = c == 0 || c == n_.x ? 0.5 : crossing(v[c - 1], v[c]);
        return toPatient(c - 1 + t, q - 1, s - 1);
    }
    glm::dvec3 yVertex(const T* v0, const T* v1, int p, int q, int s) const {
        const double t = q == 0 || q == n_.y ? 0.5 : crossing(v0[p - 1], v1[p - 1]);
        return toPatient(p - 1, q - 1 + t, s - 1);
    }
    glm::dvec3 zVertex(const T* v0, const T* v1, int p, int q, int s) const {
        const double t = s == 0 || s == n_.z ? 0.5 : crossing(v0[p - 1], v1[p - 1]);
        return toPatient(p - 1, q - 1, s - 1 + t);
    }

    // Pass 4: the vertices this row owns (x-edges of row (q, s), y- and
    // z-edges from it) and the triangles of its cells.
    void writeCellRow(int q, int s, TriangleMesh& out) const {
        const RowState& r00 = rows_[rowIndex(q, s)];
        if (r00.cellFirst > r00.cellLast) {
            return;
        }
        const RowState& r10 = rows_[rowIndex(q + 1, s)];
        const RowState& r01 = rows_[rowIndex(q, s + 1)];
        const RowState& r11 = rows_[rowIndex(q + 1, s + 1)];
        const auto start = [](const RowState& r) {
            return static_cast<std::uint32_t>(r.vertexOffset);
        };
        EdgeIds next{start(r00),
                     start(r10),
                     start(r01),
                     start(r11),
                     start(r00) + r00.xCount,
                     start(r01) + r01.xCount,
                     start(r00) + r00.xCount + r00.yCount,
                     start(r10) + r10.xCount + r10.yCount};
        glm::dvec3* vertices = out.vertices.data();
        glm::u32vec3* triangle = out.triangles.data() + r00.triangleOffset;
        const T* v00 = voxels(q, s);
        const T* v10 = voxels(q + 1, s);
        const T* v01 = voxels(q, s + 1);
        const std::uint8_t* const ec[4] = {edgeCases(q, s), edgeCases(q + 1, s),
                                           edgeCases(q, s + 1), edgeCases(q + 1, s + 1)};
        const auto& table = marchingCubesCases();
        const bool flip = settings_.flipWinding;
        const int first = r00.cellFirst, last = r00.cellLast;
        for (int c = first; c <= last; ++c) {
            if (c + 8 <= last + 1 && uncut(ec, c)) {
                c += 7;
                continue;
            }
            const unsigned cube = cubeCase(ec, c);
            if (cube == 0 || cube == 255) {
                continue;
            }
            if (cut(cube, 0, 1) != 0) {
                vertices[next.x00] = xVertex(v00, c, q, s);
            }
            if (cut(cube, 0, 2) != 0) {
                vertices[next.y00] = yVertex(v00, v10, c, q, s);
            }
            if (cut(cube, 0, 4) != 0) {
                vertices[next.z00] = zVertex(v00, v01, c, q, s);
            }
            const std::array<std::uint32_t, 12> ids = next.ofCell(cube);
            const MarchingCubesCase& mc = table[cube];
            for (int t = 0; t < 3 * mc.triangleCount; t += 3) {
                const std::uint32_t a = ids[mc.edges[t]];
                const std::uint32_t b = ids[mc.edges[t + 1]];
                const std::uint32_t d = ids[mc.edges[t + 2]];
                *triangle++ = flip ? glm::u32vec3(a, d, b) : glm::u32vec3(a, b, d);
            }
            next.pass(cube);
        }
        const unsigned lastCube = cubeCase(ec, last); // its right corner ends the row
        if (cut(lastCube, 1, 3) != 0) {
            vertices[next.y00] = yVertex(v00, v10, last + 1, q, s);
        }
        if (cut(lastCube, 1, 5) != 0) {
            vertices[next.z00] = zVertex(v00, v01, last + 1, q, s);
        }
    }

    const VoxelBlock<T>& block_;
    const ContourSettings& settings_;
    const InsideTest<T> inside_;
    const glm::ivec3 n_;
    std::vector<std::uint8_t> cases_;       // x-edge cases of the block rows, n.x + 1 each
    const std::vector<std::uint8_t> zeros_; // the x-edge cases of a row of the outside layer
    std::vector<RowState> rows_;            // every padded row, q fastest
    const glm::dmat3 linear_;
    const glm::dvec3 offset_;
};

} // namespace

template <class T>
bool contourBlock(const VoxelBlock<T>& block, const ContourSettings& settings, TriangleMesh& out) {
    if (block.size.x < 1 || block.size.y < 1 || block.size.z < 1) {
        out = TriangleMesh{};
        return true;
    }
    return FlyingEdges<T>(block, settings).run(out);
}

template bool contourBlock(const VoxelBlock<std::int16_t>&, const ContourSettings&, TriangleMesh&);
template bool contourBlock(const VoxelBlock<std::uint16_t>&, const ContourSettings&, TriangleMesh&);
template bool contourBlock(const VoxelBlock<float>&, const ContourSettings&, TriangleMesh&);

} // namespace lucent
