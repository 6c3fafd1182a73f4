#version 430 core
// The GPU ray caster: the same rays, lattice, leaping rules, filters and
// compositing as the CPU ray caster (core/raycast/RayKernel.h), over a pool of
// bricks. Ray setup runs in double precision, as on the CPU, so both sample
// the same lattice; the march runs in float.

layout(location = 0) out vec4 outColour; // premultiplied rgb, alpha
layout(location = 1) out uint outSamples;
// MIP, MinIP: (extreme value, 1) where the ray took a sample; average: (sum,
// count). What the parts of a distributed render composite from.
layout(location = 2) out vec2 outProjection;

const int kDvr = 0, kMip = 1, kMinIp = 2, kAverage = 3, kIso = 4;
const int kNearest = 0, kLinear = 1, kCubic = 2;

// View and lattice, in level-0 index space; t in patient mm.
uniform dvec3 uEye;
uniform dvec3 uForward, uRight, uUp;
uniform dmat3 uToIndex;
uniform double uTanHalfFov, uAspect;
uniform ivec2 uImageSize;
uniform double uDt;
uniform dvec3 uBoxLo, uBoxHi, uClipLo, uClipHi;

// The settings that change what the march does are compile-time constants, one
// program per combination (the renderer prepends the #defines): no branch on a
// setting survives into the loop (on llvmpipe, whose SIMD lanes execute both
// sides of every branch, that halves the time).
const int kMode = LUCENT_MODE, kInterp = LUCENT_INTERP;
const bool kPreclassify = LUCENT_PRECLASSIFY, kPreintegrate = LUCENT_PREINTEGRATE;
const bool kShading = LUCENT_SHADING, kLeap = LUCENT_LEAP;
const bool kCellsInOneBrick = LUCENT_CELLS_IN_ONE_BRICK;
// Every brick is drawn from level 0: no level arithmetic per brick.
const bool kOneLevel = LUCENT_ONE_LEVEL;
// Leaps cross the cube of leapt cells the distance map gives (uCellReach);
// DVR passes over samples in blocks that show nothing (uBlockReach).
const bool kCellReach = LUCENT_CELL_REACH, kBlockSkip = LUCENT_BLOCK_SKIP;
// Each brick's central differences sit in a second pool (nearest, trilinear),
// or, for int16 voxels, in the pool itself: texel = (gradient xyz, value), so
// a shaded sample reads one texel for both.
const bool kGradientTexture = LUCENT_GRADIENT_TEXTURE;
const bool kGradientInPool = LUCENT_GRADIENT_IN_POOL;
// A frame drawn in place is not read back: its samples are also summed per
// row here (one atomic add a pixel), so that 4 bytes a row tell the count.
const bool kRowSamples = LUCENT_ROW_SAMPLES;
// A surface shown with the volume (render/SurfaceRenderer): its opaque colour
// (premultiplied) and its distance from the eye along this pixel's ray, in
// the rays' parameter t (+inf where there is none). The ray stops there and
// its colour is composited over the surface's.
const bool kSurface = LUCENT_SURFACE;
uniform sampler2D uSurfaceColour;
uniform sampler2D uSurfaceDistance;
layout(binding = 0, r32ui) uniform uimage2D uRowSamples; // (row, 0)
// A second volume along the same rays (3D fusion; the mixing rule is in
// core/raycast/OverlaySampler.h): its values on the base's grid, level-0 index
// space, trilinear; its table (row 0: colour, opacity corrected for the step;
// row 1: colour, raw opacity), indexed as windowToGrey indexes grey.
const bool kOverlay = LUCENT_OVERLAY;
uniform sampler3D uOverlay;
uniform sampler2D uOverlayTable;
uniform float uOverlayLow, uOverlayWidth;
uniform vec3 uOverlayInvDims;
// Fused DVR leaps only where the overlay shows nothing either: 1 per leaping cell
// and per page where every overlay voxel its samples can read lies below the
// window's first visible entry (render/OverlayTextures.h).
uniform usampler3D uOverlayEmptyCells;
uniform usampler3D uOverlayEmptyBricks;
uniform float uEarlyTermination, uIso;
uniform vec4 uLight; // ambient, diffuse, specular, specular power
uniform mat3 uGradientToWorld;
uniform float uVisibleLo, uVisibleHi;

// Each level's dimensions (level n's position of level-0 p is
// (p - (2^n - 1) / 2) / 2^n).
uniform ivec3 uLevelDims[8];

// Bricks (render/BrickTable.h, pageEntry): one texel a brick, the atlas texel
// of its level's voxel 0 (16 bits an axis, signed), its state (0 absent, 1
// resident, 2 resident only for its border: leapt over, read there) and level,
// and the level-0 samples [lo, hi) it backs from its first voxel (10 bits an axis).
uniform int uBrickSize;
uniform float uInvBrickSize;
uniform ivec3 uBricksPerAxis;
uniform vec3 uInvPoolSize;
uniform usampler3D uPageEntry;
uniform sampler3D uPool;
uniform float uValueScale; // texture value -> data value
uniform sampler3D uGradientPool;
uniform float uGradientScale; // texture value -> half the difference of the neighbours

// Transfer function: row 0 alpha corrected for dt, row 1 alpha per dt_ref.
uniform sampler2D uTable;
uniform int uTableSize;
uniform float uTableLo, uTableScale;
uniform sampler2D uPreTable;
uniform int uPreSize;
uniform float uPreLo, uPreHi;

#include "raycast_sampling.glsl"

// --- the ray --------------------------------------------------------------------

void writeSamples(uint samples) {
    outSamples = samples;
    if (kRowSamples && samples != 0u) {
        imageAtomicAdd(uRowSamples, ivec2(int(gl_FragCoord.y), 0), samples);
    }
}

// A part of a volume drawn alone (core/volume/VolumePart.h): its box's shared
// hi faces are open, and the description's clip box bounds the lead-in sample.
uniform int uPart;
uniform ivec3 uOpenHi;
uniform dvec3 uSceneClipLo, uSceneClipHi;

// raySpanIn (core/raycast/RaySetup.h): the box anchors the lattice; the clip
// box is closed but on the hi faces openHi names.
bool raySpanIn(dvec3 o, dvec3 d, dvec3 clipLo, dvec3 clipHi, ivec3 openHi, out double t0,
               out int nFirst, out int nLast) {
    t0 = -1.0e300LF;
    double t1 = 1.0e300LF, c0 = t0, c1 = t1;
    bool c0Open = false, c1Open = false;
    nFirst = 0;
    nLast = -1;
    for (int a = 0; a < 3; ++a) {
        if (abs(d[a]) < 1e-15) {
            if (o[a] < uBoxLo[a] || o[a] > uBoxHi[a] || o[a] < clipLo[a] || o[a] > clipHi[a] ||
                (openHi[a] != 0 && o[a] >= clipHi[a])) {
                return false;
            }
            continue;
        }
        double ta = (uBoxLo[a] - o[a]) / d[a], tb = (uBoxHi[a] - o[a]) / d[a];
        t0 = max(t0, min(ta, tb));
        t1 = min(t1, max(ta, tb));
        double ca = (clipLo[a] - o[a]) / d[a], cb = (clipHi[a] - o[a]) / d[a];
        double enter = min(ca, cb), leave = max(ca, cb);
        bool enterOpen = openHi[a] != 0 && d[a] < 0.0, leaveOpen = openHi[a] != 0 && d[a] > 0.0;
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
    t0 = max(t0, 0.0);
    double tEnd = min(t1, c1);
    if (t1 < t0 || tEnd < max(t0, c0)) {
        return false;
    }
    if (c0Open && c0 >= t0) {
        nFirst = int(floor((c0 - t0) / uDt + 1e-9)) + 1;
    } else {
        nFirst = c0 > t0 ? int(ceil((c0 - t0) / uDt - 1e-9)) : 0;
    }
    if (c1Open && c1 <= t1) {
        nLast = int(ceil((c1 - t0) / uDt - 1e-9)) - 1;
    } else {
        nLast = int(floor((tEnd - t0) / uDt + 1e-9));
    }
    return true;
}

// The last sample in front of the surface: n with t0 + n * dt < tS (a
// sample exactly at the surface belongs to it), no earlier than nFirst - 1.
int lastBeforeSurface(double t0, int nFirst, int nLast) {
    float tS = texelFetch(uSurfaceDistance, ivec2(gl_FragCoord.xy), 0).r;
    if (!(tS < 3.0e38)) {
        return nLast;
    }
    double before = ceil((double(tS) - t0) / uDt) - 1.0;
    return int(clamp(before, double(nFirst - 1), double(nLast)));
}

void castRay() {
    outColour = vec4(0.0);
    outSamples = 0u;
    outProjection = vec2(0.0);
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    // y = 0 is the top row, as in the CPU image.
    double sx = (2.0 * (double(pixel.x) + 0.5) / double(uImageSize.x) - 1.0) * uTanHalfFov * uAspect;
    double sy = (1.0 - 2.0 * (double(uImageSize.y - 1 - pixel.y) + 0.5) / double(uImageSize.y)) * uTanHalfFov;
    dvec3 wd = normalize(uForward + uRight * sx + uUp * sy);
    dvec3 o = uEye;
    dvec3 d = uToIndex * wd;
    vec3 w = vec3(wd);

    // raySpan (core/raycast/RaySetup.h), in double as on the CPU.
    double t0;
    int nFirst, nLast;
    if (!raySpanIn(o, d, uClipLo, uClipHi, uOpenHi, t0, nFirst, nLast)) {
        return;
    }
    // A part of a volume: crossings and segments across a shared face start
    // one sample early (previousSampleShared in RaySetup.h).
    if (uPart != 0 && (kPreintegrate || kMode == kIso) && nFirst <= nLast) {
        double sceneT0;
        int sceneFirst, sceneLast;
        if (raySpanIn(o, d, uSceneClipLo, uSceneClipHi, ivec3(0), sceneT0, sceneFirst, sceneLast) &&
            nFirst - 1 >= sceneFirst) {
            nFirst -= 1;
        }
    }

    if (kSurface) {
        nLast = lastBeforeSurface(t0, nFirst, nLast);
    }

    vec3 entry = vec3(o + d * t0), stride = vec3(d * uDt);
    setRayLattice(entry, stride);
    bool continuity = kPreintegrate || kMode == kIso;
    vec4 acc = vec4(0.0);
    float extreme = kMode == kMinIp ? 3.0e38 : -3.0e38;
    double sum = 0.0;
    int count = 0;
    bool havePrev = false;
    float prev = 0.0;
    int nPrev = 0;
    uint samples = 0u;
    ivec3 cell = ivec3(-1);
    uint code = 0u;
    ivec3 block = ivec3(-1);
    int blockReach = 0;

    float overlayMax = 0.0;
    bool overlaySeen = false;
    for (int n = nFirst; n <= nLast; ++n) {
        vec3 p = entry + stride * float(n);
        vec3 lattice = p; // where the overlay is sampled, whatever the base's filter
        if (kInterp == kNearest) {
            // The voxel the sample reads decides the brick too: where bricks of
            // different levels meet, the one holding that voxel answers.
            p = floor(p + 0.5);
        }
        ivec3 c = min(ivec3(p * uInvCellSize), uCellsPerAxis - 1);
        if (c != cell) {
            cell = c;
            // With the distance map, one fetch gives the code and the reach.
            uint cellBits = kCellReach ? texelFetch(uCellReach, c, 0).r : texelFetch(uCellCode, c, 0).r;
            code = kCellReach ? cellBits & 3u : cellBits;
            if (kCellsInOneBrick) {
                enterBrick(brickOf(p));
            }
            bool leap = false;
            vec3 lo, hi;
            if (kLeap) {
                if (kMode == kMip || kMode == kMinIp) {
                    vec2 r = texelFetch(uCellRange, c, 0).rg;
                    leap = havePrev && (kMode == kMip ? r.y <= extreme : r.x >= extreme);
                    lo = vec3(c * uCellSize);
                    hi = lo + float(uCellSize);
                } else if (code != 0u && kMode != kAverage) {
                    ivec3 b = brickOf(p);
                    // With an overlay: the brick only where it is empty too, else
                    // the cell (code 2 lets the base leap every cell of the brick).
                    bool brick = code == 2u &&
                                 (!kOverlay || texelFetch(uOverlayEmptyBricks, b, 0).r != 0u);
                    leap = brick || !kOverlay || texelFetch(uOverlayEmptyCells, c, 0).r != 0u;
                    lo = vec3(brick ? b * uBrickSize : c * uCellSize);
                    hi = lo + float(brick ? uBrickSize : uCellSize);
                }
            }
            if (leap) {
                // With the distance maps, a leap without continuity resumes at
                // the first sample not inside the boxes shrunk by a hundredth
                // of a voxel (the rounding of positions), else one sample early
                // (also for nearest, whose samples read half a voxel further).
                bool tight = kCellReach && !continuity && kInterp != kNearest;
                float shrink = tight ? 0.01 : 0.0;
                float exit = exitIndex(lo + shrink, hi - shrink);
                if (kCellReach && !kOverlay && kMode != kMip && kMode != kMinIp) {
                    // The cube of leapt cells around this one, where it reaches further.
                    int r = int(cellBits >> 2u);
                    exit = max(exit, exitIndex(vec3((c - r) * uCellSize) + shrink,
                                               vec3((c + r + 1) * uCellSize) - shrink));
                }
                int resume = tight ? max(n + 1, int(ceil(exit))) : max(n + 1, int(floor(exit)) - 1);
                if (!continuity) {
                    n = resume - 1;
                    continue;
                }
                // As on the CPU: sample n and the last one before `resume` are
                // read, so that crossings and segments at the border survive.
                enterBrick(brickOf(p));
                bool known = backed(p);
                float vn = known ? valueAt(p) : prev;
                ++samples;
                bool crossing = kMode == kIso && havePrev && known && ((prev < uIso) != (vn < uIso));
                if (!crossing && resume - 1 > n) {
                    vec3 pl = entry + stride * float(resume - 1);
                    enterBrick(brickOf(pl));
                    havePrev = backed(pl);
                    prev = havePrev ? valueAt(pl) : 0.0;
                    nPrev = resume - 1;
                    ++samples;
                    n = resume - 1;
                    cell = ivec3(-1);
                    continue;
                }
            }
        }
        if (kBlockSkip) {
            // A block that shows nothing, and the cube of such blocks around
            // it: resume at the first sample not inside the cube, shrunk by a
            // hundredth of a voxel for the rounding of positions.
            ivec3 b = min(ivec3(p * 0.5), uBlocksPerAxis - 1);
            if (b != block) { // a block holds about four samples: read it once
                block = b;
                blockReach = int(texelFetch(uBlockReach, b, 0).r);
            }
            int r = blockReach;
            if (r != 0) {
                vec3 lo = vec3((b - (r - 1)) * 2) + 0.01, hi = vec3((b + r) * 2) - 0.01;
                n = max(n, int(ceil(exitIndex(lo, hi))) - 1);
                continue;
            }
        }
        if (!kCellsInOneBrick) {
            enterBrick(brickOf(p));
        }
        ++samples;
        bool isBacked = backed(p);
        if (kOverlay && kMode != kDvr) {
            float ov = overlayValue(lattice);
            if (!isnan(ov) && (!overlaySeen || ov > overlayMax)) {
                overlayMax = ov;
                overlaySeen = true;
            }
        }
        if (!isBacked) {
            // Outside the boxes of resident bricks nothing of the base can
            // contribute; a value read across it is unknown.
            havePrev = havePrev && !continuity;
            if (kOverlay && kMode == kDvr) {
                vec4 k = fuse(vec4(0.0), overlayEntry(overlayValue(lattice), 0));
                if (k.a > 0.0) {
                    acc += vec4((1.0 - acc.a) * k.a * k.rgb, (1.0 - acc.a) * k.a);
                    if (acc.a >= uEarlyTermination) {
                        break;
                    }
                }
            }
            continue;
        }
        float v = valueAt(p);
        if (kMode == kMip) {
            extreme = max(extreme, v);
            havePrev = true;
            continue;
        }
        if (kMode == kMinIp) {
            extreme = min(extreme, v);
            havePrev = true;
            continue;
        }
        if (kMode == kAverage) {
            sum += double(v);
            ++count;
            continue;
        }
        if (kMode == kIso) {
            if (havePrev && (prev < uIso) != (v < uIso)) {
                // Bisection between the two lattice samples for the crossing.
                double a = t0 + double(nPrev) * uDt, b = t0 + double(n) * uDt;
                float va = prev;
                for (int it = 0; it < 40 && b - a > 1e-9 * uDt; ++it) {
                    double m = 0.5 * (a + b);
                    vec3 pm = vec3(o + d * m);
                    enterBrick(brickOf(pm));
                    float vm = valueAt(pm);
                    if ((va < uIso) == (vm < uIso)) {
                        a = m;
                        va = vm;
                    } else {
                        b = m;
                    }
                }
                vec3 hit = vec3(o + d * (0.5 * (a + b)));
                enterBrick(brickOf(hit));
                vec4 k = classify(uIso, 1);
                outColour = vec4(kShading ? shade(k.rgb, hit, w) : k.rgb, 1.0);
                writeSamples(samples);
                return;
            }
            prev = v;
            nPrev = n;
            havePrev = true;
            continue;
        }

        if (kOverlay) { // DVR: the base's sample, shaded, mixed with the overlay's
            vec4 k = vec4(0.0);
            if (kPreintegrate) {
                if (havePrev) {
                    vec4 seg = preintegrated(prev, v);
                    k = seg.a > 0.0 ? vec4(seg.rgb / seg.a, seg.a) : vec4(0.0);
                }
                prev = v;
                havePrev = true;
            } else if (kPreclassify || (v >= uVisibleLo && v <= uVisibleHi)) {
                k = kPreclassify && kInterp != kNearest ? preclassified(p) : classify(v, 0);
            }
            if (k.a > 0.0 && kShading) {
                k.rgb = shadeLast(k.rgb, p, w);
            }
            k = fuse(k, overlayEntry(overlayValue(lattice), 0));
            if (k.a > 0.0) {
                float weight = (1.0 - acc.a) * k.a;
                acc += vec4(weight * k.rgb, weight);
                if (acc.a >= uEarlyTermination) {
                    break;
                }
            }
            continue;
        }

        vec4 k;
        if (kPreintegrate) {
            if (!havePrev) {
                prev = v;
                havePrev = true;
                continue;
            }
            vec4 seg = preintegrated(prev, v);
            prev = v;
            if (seg.a <= 0.0) {
                continue;
            }
            k = vec4(seg.rgb / seg.a, seg.a);
        } else {
            if (!kPreclassify && (v < uVisibleLo || v > uVisibleHi)) {
                continue;
            }
            k = kPreclassify && kInterp != kNearest ? preclassified(p) : classify(v, 0);
        }
        if (k.a <= 0.0) {
            continue;
        }
        vec3 rgb = kShading ? shadeLast(k.rgb, p, w) : k.rgb;
        float weight = (1.0 - acc.a) * k.a;
        acc += vec4(weight * rgb, weight);
        if (acc.a >= uEarlyTermination) {
            break;
        }
    }

    writeSamples(samples);
    if (kMode == kMip || kMode == kMinIp || kMode == kAverage) {
        bool any = kMode == kAverage ? count > 0 : havePrev;
        if (any) {
            outProjection = kMode == kAverage ? vec2(float(sum), float(count)) : vec2(extreme, 1.0);
            float v = kMode == kAverage ? float(sum / double(count)) : extreme;
            vec4 k = classify(v, 1);
            outColour = vec4(k.rgb * k.a, k.a);
            if (kOverlay && overlaySeen) { // the overlay's maximum over the projection
                vec4 o = overlayEntry(overlayMax, 1);
                outColour = outColour * (1.0 - o.a) + vec4(o.rgb * o.a, o.a);
            }
        }
        return;
    }
    outColour = acc;
}

void main() {
    castRay();
    if (kSurface) {
        outColour += (1.0 - outColour.a) * texelFetch(uSurfaceColour, ivec2(gl_FragCoord.xy), 0);
    }
}
