#include "core/surface/MarchingCubesTable.h"

#include <stdexcept>

// The table is built by constant evaluation: a rule that cannot be met (a throw
// below) fails the build instead of producing a bad table.

namespace lucent {

namespace {

// Points in doubled cube coordinates (0, 1 or 2), so edge midpoints are integers.
struct Point {
    int v[3];
};

constexpr Point minus(const Point& a, const Point& b) {
    return {{a.v[0] - b.v[0], a.v[1] - b.v[1], a.v[2] - b.v[2]}};
}
constexpr Point cross(const Point& a, const Point& b) {
    return {{a.v[1] * b.v[2] - a.v[2] * b.v[1], a.v[2] * b.v[0] - a.v[0] * b.v[2],
             a.v[0] * b.v[1] - a.v[1] * b.v[0]}};
}
constexpr int dot(const Point& a, const Point& b) {
    return a.v[0] * b.v[0] + a.v[1] * b.v[1] + a.v[2] * b.v[2];
}

constexpr int bit(int corner, int axis) {
    return (corner >> axis) & 1;
}
constexpr Point cornerPoint(int c) {
    return {{2 * bit(c, 0), 2 * bit(c, 1), 2 * bit(c, 2)}};
}
constexpr Point edgePoint(int e) {
    const auto [a, b] = marchingCubesEdgeCorners(e);
    const Point pa = cornerPoint(a), pb = cornerPoint(b);
    return {{(pa.v[0] + pb.v[0]) / 2, (pa.v[1] + pb.v[1]) / 2, (pa.v[2] + pb.v[2]) / 2}};
}

// Face f = 2 * axis + side holds the corners whose coordinate on axis is side;
// its normal points out of the cube.
constexpr bool cornerOnFace(int c, int f) {
    return bit(c, f / 2) == f % 2;
}
constexpr bool edgeOnFace(int e, int f) {
    return e / 4 != f / 2 && cornerOnFace(marchingCubesEdgeCorners(e)[0], f);
}
constexpr bool edgesShareFace(int e1, int e2) {
    for (int f = 0; f < 6; ++f) {
        if (edgeOnFace(e1, f) && edgeOnFace(e2, f)) {
            return true;
        }
    }
    return false;
}
constexpr Point faceNormal(int f) {
    Point n{{0, 0, 0}};
    n.v[f / 2] = f % 2 == 1 ? 1 : -1;
    return n;
}

constexpr bool inside(int cubeCase, int c) {
    return ((cubeCase >> c) & 1) != 0;
}
constexpr bool cut(int cubeCase, int e) {
    const auto [a, b] = marchingCubesEdgeCorners(e);
    return inside(cubeCase, a) != inside(cubeCase, b);
}

// Records the face segment between the points on edges e1 and e2, directed so
// that the inside corner c lies to its right seen from outside the cube: then
// the loops run counter-clockwise seen from outside the solid.
constexpr void addSegment(std::array<int, 12>& next, int e1, int e2, int c, int f) {
    const Point a = edgePoint(e1);
    const int side = dot(cross(minus(edgePoint(e2), a), minus(cornerPoint(c), a)), faceNormal(f));
    if (side == 0) {
        throw std::logic_error("marching cubes: corner on a segment");
    }
    const int from = side < 0 ? e1 : e2;
    const int to = side < 0 ? e2 : e1;
    if (next[from] != -1) {
        throw std::logic_error("marching cubes: two segments leave one edge");
    }
    next[from] = to;
}

// The segments of one face under the face rule.
constexpr void addFaceSegments(std::array<int, 12>& next, int cubeCase, int f) {
    int cutEdges[4] = {};
    int count = 0;
    for (int e = 0; e < 12; ++e) {
        if (edgeOnFace(e, f) && cut(cubeCase, e)) {
            cutEdges[count++] = e;
        }
    }
    if (count == 0) {
        return;
    }
    for (int c = 0; c < 8; ++c) {
        if (!cornerOnFace(c, f) || !inside(cubeCase, c)) {
            continue;
        }
        if (count == 2) {
            addSegment(next, cutEdges[0], cutEdges[1], c, f);
            return;
        }
        // Ambiguous face: cut off each inside corner by its own segment.
        int around[2] = {};
        int n = 0;
        for (int i = 0; i < 4; ++i) {
            const auto [a, b] = marchingCubesEdgeCorners(cutEdges[i]);
            if (a == c || b == c) {
                around[n++] = cutEdges[i];
            }
        }
        addSegment(next, around[0], around[1], c, f);
    }
}

struct Loop {
    int edges[12] = {};
    int size = 0;
};

// A minimum-weight triangulation (sum of squared chord lengths) of a loop that
// uses no chord between two edges of one face. Appends to the case.
constexpr void triangulate(const Loop& loop, MarchingCubesCase& out) {
    constexpr int kForbidden = 1 << 28;
    const int n = loop.size;
    const auto chordCost = [&](int i, int j) {
        if (j == i + 1 || (i == 0 && j == n - 1)) {
            return 0; // a side of the loop, not a chord
        }
        const int a = loop.edges[i], b = loop.edges[j];
        if (edgesShareFace(a, b)) {
            return kForbidden;
        }
        const Point d = minus(edgePoint(a), edgePoint(b));
        return dot(d, d);
    };
    int cost[12][12] = {};
    int apex[12][12] = {};
    for (int span = 2; span < n; ++span) {
        for (int i = 0; i + span < n; ++i) {
            const int j = i + span;
            cost[i][j] = kForbidden;
            for (int k = i + 1; k < j; ++k) {
                const int c = cost[i][k] + cost[k][j] + chordCost(i, k) + chordCost(k, j);
                if (c < cost[i][j]) {
                    cost[i][j] = c;
                    apex[i][j] = k;
                }
            }
        }
    }
    if (cost[0][n - 1] >= kForbidden) {
        throw std::logic_error("marching cubes: no triangulation obeys the chord rule");
    }
    // Emit the triangles (i, k, j) of the chosen tree, keeping the loop's order.
    int stack[12][2] = {{0, n - 1}};
    int depth = 1;
    while (depth > 0) {
        const auto [i, j] = stack[--depth];
        if (j - i < 2) {
            continue;
        }
        const int k = apex[i][j];
        if (out.triangleCount >= kMarchingCubesMaxTriangles) {
            throw std::logic_error("marching cubes: too many triangles in one case");
        }
        const int t = 3 * out.triangleCount++;
        out.edges[t] = static_cast<std::uint8_t>(loop.edges[i]);
        out.edges[t + 1] = static_cast<std::uint8_t>(loop.edges[k]);
        out.edges[t + 2] = static_cast<std::uint8_t>(loop.edges[j]);
        stack[depth][0] = i;
        stack[depth++][1] = k;
        stack[depth][0] = k;
        stack[depth++][1] = j;
    }
}

constexpr MarchingCubesCase makeCase(int cubeCase) {
    std::array<int, 12> next{};
    next.fill(-1);
    for (int f = 0; f < 6; ++f) {
        addFaceSegments(next, cubeCase, f);
    }
    MarchingCubesCase out;
    bool visited[12] = {};
    for (int start = 0; start < 12; ++start) {
        if (!cut(cubeCase, start) || visited[start]) {
            continue;
        }
        Loop loop;
        int e = start;
        do {
            if (e < 0 || !cut(cubeCase, e) || visited[e]) {
                throw std::logic_error("marching cubes: a loop does not close");
            }
            visited[e] = true;
            loop.edges[loop.size++] = e;
            e = next[e];
        } while (e != start);
        triangulate(loop, out);
    }
    return out;
}

constexpr std::array<MarchingCubesCase, 256> makeTable() {
    std::array<MarchingCubesCase, 256> table{};
    for (int c = 0; c < 256; ++c) {
        table[c] = makeCase(c);
    }
    return table;
}

constexpr std::array<MarchingCubesCase, 256> kCases = makeTable();

constexpr int triangleTotal() {
    int total = 0;
    for (const MarchingCubesCase& c : kCases) {
        total += c.triangleCount;
    }
    return total;
}

// The face rule fixes the loops, and a loop of n points always gives n - 2
// triangles: 820 over all cases.
static_assert(triangleTotal() == 820);
static_assert(kCases[0].triangleCount == 0 && kCases[255].triangleCount == 0);

} // namespace

const std::array<MarchingCubesCase, 256>& marchingCubesCases() {
    return kCases;
}

} // namespace lucent
