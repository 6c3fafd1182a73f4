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
    // A part of a volume drawn alone (core/volume/VolumePart.h): the box is the
    // whole volume's and anchors the lattice; the clip box is the part's owned
    // box within the description's clip box (sceneClipLo .. sceneClipHi), with
    // its shared hi faces open. Coordinates are the part's indices.
    bool part = false;
    glm::bvec3 openHi{false};
    glm::dvec3 sceneClipLo{0.0}, sceneClipHi{0.0};
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
    // MIP and MinIP: the projected value and 1; average: the sum of the
    // samples and their count; (0, 0) where the ray took no sample.
    glm::dvec2 projection{0.0};
};

// The samples a ray takes: t0 + n * dt for n in [nFirst, nLast], t0 where it
// enters the volume box (the lattice's anchor), clipped to the clip box.
struct RaySpan {
    double t0 = 0.0;
    long nFirst = 0, nLast = -1;
};

// raySpan over an explicit box and clip box: the clip box is closed except on
// the hi faces openHi names, where a sample exactly on the face is left out
// (the neighbouring box, closed there, takes it).
inline bool raySpanIn(const glm::dvec3& boxLo, const glm::dvec3& boxHi, const glm::dvec3& clipLo,
                      const glm::dvec3& clipHi, const glm::bvec3& openHi, double dt,
                      const glm::dvec3& o, const glm::dvec3& d, RaySpan& span) {
    double t0 = -std::numeric_limits<double>::infinity(),
           t1 = std::numeric_limits<double>::infinity();
    double c0 = t0, c1 = t1;
    bool c0Open = false, c1Open = false;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-15) {
            if (o[a] < boxLo[a] || o[a] > boxHi[a] || o[a] < clipLo[a] || o[a] > clipHi[a] ||
                (openHi[a] && o[a] >= clipHi[a])) {
                return false;
            }
            continue;
        }
        const double ta = (boxLo[a] - o[a]) / d[a], tb = (boxHi[a] - o[a]) / d[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
        // Most renders clip nothing: the clip planes are the box's, and so are
        // their distances (the same divisions, not done twice).
        const bool unclipped = clipLo[a] == boxLo[a] && clipHi[a] == boxHi[a];
        const double ca = unclipped ? ta : (clipLo[a] - o[a]) / d[a];
        const double cb = unclipped ? tb : (clipHi[a] - o[a]) / d[a];
        // An open hi face is where a ray towards lower indices enters, and
        // where one towards higher indices leaves.
        const double enter = std::min(ca, cb), leave = std::max(ca, cb);
        const bool enterOpen = openHi[a] && d[a] < 0.0, leaveOpen = openHi[a] && d[a] > 0.0;
        if (enter > c0) {
            c0 = enter;
            c0Open = enterOpen;
        } else if (enter == c0) {
            c0Open = c0Open || enterOpen;
        }
        if (leave < c1) {
            c1 = leave;
            c1Open = leaveOpen;
        } else if (leave == c1) {
            c1Open = c1Open || leaveOpen;
        }
    }
    t0 = std::max(t0, 0.0);
    const double tEnd = std::min(t1, c1);
    if (t1 < t0 || tEnd < std::max(t0, c0)) {
        return false;
    }
    span.t0 = t0;
    // A closed face takes the samples within 1e-9 steps of it; an open face
    // leaves out exactly those its closed neighbour takes.
    if (c0Open && c0 >= t0) {
        span.nFirst = long(std::floor((c0 - t0) / dt + 1e-9)) + 1;
    } else {
        span.nFirst = c0 > t0 ? long(std::ceil((c0 - t0) / dt - 1e-9)) : 0;
    }
    if (c1Open && c1 <= t1) {
        span.nLast = long(std::ceil((c1 - t0) / dt - 1e-9)) - 1;
    } else {
        span.nLast = long(std::floor((tEnd - t0) / dt + 1e-9));
    }
    return true;
}

// False when the ray misses the box or the clip box.
template <class Real>
bool raySpan(const RaySetup<Real>& s, const glm::dvec3& o, const glm::dvec3& d, RaySpan& span) {
    return raySpanIn(s.boxLo, s.boxHi, s.clipLo, s.clipHi, s.openHi, s.dt, o, d, span);
}

// For a part: whether the sample before span.nFirst lies in another part's box
// (within the description's clip box). Kernels that need the previous sample
// (isosurface crossings, pre-integrated segments) start there, so that the
// segment across a shared face is drawn by the part behind it.
template <class Real>
bool previousSampleShared(const RaySetup<Real>& s, const glm::dvec3& o, const glm::dvec3& d,
                          const RaySpan& span) {
    if (!s.part || span.nFirst > span.nLast) {
        return false;
    }
    RaySpan scene;
    return raySpanIn(s.boxLo, s.boxHi, s.sceneClipLo, s.sceneClipHi, glm::bvec3(false), s.dt, o, d,
                     scene) &&
           span.nFirst - 1 >= scene.nFirst;
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
