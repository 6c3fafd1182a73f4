#pragma once
// What every CPU ray kernel shares: the per-render setup, the span of lattice
// samples a ray takes, and where a ray leaves a leaping cell. Private to
// core/raycast.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/scene/RenderDescription.h"
#include "core/tf/SegmentPreintegrator.h"

namespace lucent {

struct InvisibleCells;

// Everything a ray needs that does not change from pixel to pixel.
template <class Real> struct RaySetup {
    RenderMode mode = RenderMode::Dvr;
    Classification classification = Classification::Post;
    bool preintegrate = false;
    bool shading = false;
    bool exactTf = false; // evaluate the transfer function itself (reference) instead of the table
    const TransferFunction* tf = nullptr;
    Shading light;
    double stepRatio = 1.0; // dt / dt_ref
    double dt = 1.0;        // mm
    Real earlyTermination = Real(0.99);
    double isoValue = 0.0;
    glm::dmat3 gradientToWorld{1.0};   // inverse transpose of the index-to-patient linear part
    glm::dvec3 boxLo{0.0}, boxHi{0.0}; // volume box (voxel centres) in index space
    glm::dvec3 clipLo{0.0}, clipHi{0.0};
    // Tables (float precision path).
    const std::vector<glm::vec4>* table =
        nullptr; // rgb (not premultiplied), alpha corrected for dt
    const std::vector<glm::vec4>* rawTable =
        nullptr; // the same with alpha per dt_ref (pre-classification)
    double tableLo = 0.0, tableScale = 1.0;
    const PreintegrationTable* preTable = nullptr;
    // Double precision (exactTf): each segment integrated exactly, no table.
    const SegmentPreintegrator* exactSegments = nullptr;
    // Samples whose value lies outside [visibleLo, visibleHi] are transparent
    // (post-classification DVR): they need no table lookup.
    double visibleLo = -std::numeric_limits<double>::infinity();
    double visibleHi = std::numeric_limits<double>::infinity();
    // Trilinear cells whose samples all lie outside [visibleLo, visibleHi]
    // (packet kernel). Null: none built.
    const InvisibleCells* invisibleCells = nullptr;
    // Empty-space leaping over two levels: the bricks, then finer cells inside
    // the bricks that cannot be leapt. skippable[] holds the static decisions
    // (DVR, iso); range[] the min/max that MIP/MinIP decide on as they go.
    struct LeapLevel {
        int size = 64;
        Real inverseSize = Real(1) / Real(64);
        glm::ivec3 perAxis{1};
        const std::vector<std::uint8_t>* skippable = nullptr;
        const std::vector<glm::vec2>* range = nullptr;
    };
    bool leap = false;
    LeapLevel levels[2];
    // Per cell of levels[1]: 2 where its whole brick can be leapt, 1 where the
    // cell can, 0 where neither (the fast kernel's one lookup per cell).
    const std::vector<std::uint8_t>* cellLeap = nullptr;
    // Per cell of levels[1] that can be leapt: r such that all cells within r
    // cells of it, in every direction, can be leapt too (see LeapReach.h); the
    // fast kernels leap over that whole cube. Null: r = 0.
    const std::vector<std::uint8_t>* cellReach = nullptr;
    // Per cell of levels[1]: cellLeap | cellReach << 8, for kernels that look
    // up both in one load (the packet kernel's gather). Null: none built.
    const std::vector<std::int32_t>* cellLeapReach = nullptr;
};

struct RayOutput {
    glm::dvec4 rgba{0.0}; // premultiplied colour, alpha
    std::size_t samples = 0;
};

// The samples a ray takes: t0 + n * dt for n in [nFirst, nLast], t0 where it
// enters the volume box (the lattice's anchor), clipped to the clip box.
struct RaySpan {
    double t0 = 0.0;
    long nFirst = 0, nLast = -1;
};

// False when the ray misses the box or the clip box.
template <class Real>
bool raySpan(const RaySetup<Real>& s, const glm::dvec3& o, const glm::dvec3& d, RaySpan& span) {
    double t0 = -std::numeric_limits<double>::infinity(),
           t1 = std::numeric_limits<double>::infinity();
    double c0 = t0, c1 = t1;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-15) {
            if (o[a] < s.boxLo[a] || o[a] > s.boxHi[a] || o[a] < s.clipLo[a] ||
                o[a] > s.clipHi[a]) {
                return false;
            }
            continue;
        }
        const double ta = (s.boxLo[a] - o[a]) / d[a], tb = (s.boxHi[a] - o[a]) / d[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
        // Most renders clip nothing: the clip planes are the box's, and so are
        // their distances (the same divisions, not done twice).
        const bool unclipped = s.clipLo[a] == s.boxLo[a] && s.clipHi[a] == s.boxHi[a];
        const double ca = unclipped ? ta : (s.clipLo[a] - o[a]) / d[a];
        const double cb = unclipped ? tb : (s.clipHi[a] - o[a]) / d[a];
        c0 = std::max(c0, std::min(ca, cb));
        c1 = std::min(c1, std::max(ca, cb));
    }
    t0 = std::max(t0, 0.0);
    const double tEnd = std::min(t1, c1);
    if (t1 < t0 || tEnd < std::max(t0, c0)) {
        return false;
    }
    span.t0 = t0;
    span.nFirst = c0 > t0 ? long(std::ceil((c0 - t0) / s.dt - 1e-9)) : 0;
    span.nLast = long(std::floor((tEnd - t0) / s.dt + 1e-9));
    return true;
}

// Patient distance at which the ray o + t d leaves the core region of the
// cell at idx (cells of `size` voxels, perAxis of them), never before t.
inline double leapCellExit(int size, glm::ivec3 perAxis, glm::ivec3 idx, const glm::dvec3& o,
                           const glm::dvec3& d, double t) {
    double exit = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        const double lo = double(idx[a] * size);
        const double hi = lo + double(size);
        if (d[a] > 1e-15 && idx[a] < perAxis[a] - 1) {
            exit = std::min(exit, (hi - o[a]) / d[a]);
        } else if (d[a] < -1e-15 && idx[a] > 0) {
            exit = std::min(exit, (lo - o[a]) / d[a]);
        }
    }
    return std::max(exit, t);
}

} // namespace lucent
