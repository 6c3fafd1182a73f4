#pragma once
// The marching-cubes case table: for each of the 256 inside/outside patterns of
// a cube's corners, the triangles that separate the inside corners from the
// outside ones, as triples of cube edges. It is generated at compile time in
// MarchingCubesTable.cpp from two rules, so that neighbouring cubes always
// agree on their shared face and the surface is closed and manifold:
//  * face rule: on an ambiguous face (two diagonal corners inside, two
//    outside) the two inside corners are separated (the outside corners
//    connect across the face);
//  * chord rule: a loop of edge points is never triangulated with a chord
//    whose two ends lie on the same cube face (such a chord would lie in the
//    face and could meet a triangle of the neighbouring cube).
//
// Numbering:
//  * corner c sits at (x, y, z) = (c & 1, (c >> 1) & 1, (c >> 2) & 1);
//  * edge e runs along axis e / 4 (0 = x, 1 = y, 2 = z) from its low corner to
//    its high corner; its other two coordinates, in axis order, are
//    (e & 1, (e >> 1) & 1): x edges 0-3 sit at (y, z) = (0,0) (1,0) (0,1)
//    (1,1), y edges 4-7 at (x, z), z edges 8-11 at (x, y), in the same order;
//  * case bit c is set when corner c is inside (value >= iso).
// Orientation: each triangle (e0, e1, e2) is counter-clockwise seen from the
// outside, so the right-hand normal (p1 - p0) x (p2 - p0) points from the
// inside corners towards the outside ones (out of the solid), in a right-handed
// index frame.

#include <array>
#include <cstdint>

namespace lucent {

inline constexpr int kMarchingCubesMaxTriangles = 5; // per case

struct MarchingCubesCase {
    std::uint8_t triangleCount = 0;
    std::array<std::uint8_t, 3 * kMarchingCubesMaxTriangles> edges{}; // 3 per triangle
};

// The corner at the low (index 0) and the high (index 1) end of edge e.
constexpr std::array<int, 2> marchingCubesEdgeCorners(int edge) {
    const int axis = edge / 4;
    const int a = edge & 1;
    const int b = (edge >> 1) & 1;
    const int low = axis == 0 ? (a << 1) | (b << 2) : axis == 1 ? a | (b << 2) : a | (b << 1);
    return {low, low | (1 << axis)};
}

// All 256 cases, indexed by the case bits. Built once, at compile time.
const std::array<MarchingCubesCase, 256>& marchingCubesCases();

} // namespace lucent
