// Included by raycast.frag (render/GlObjects.cpp expands #include before compiling): the
// bricks, the filters, the transfer function and shading, leaping and the overlay, on the
// uniforms raycast.frag declares.
// --- the brick a position lies in -------------------------------------------

ivec3 gBrick = ivec3(-1);
int gState = 0;             // of the current brick: 0 absent, 1 resident, 2 border only
vec3 gSlotBase = vec3(0.0); // atlas texel of its level's voxel 0
vec3 gBoxLo = vec3(1.0e30), gBoxHi = vec3(-1.0e30); // the samples it backs
// With kOneLevel the scale and offset keep these values and gDims is set once
// per ray (setRayLattice): assigned per brick, even as constants, they cost 4 %
// of the llvmpipe frame.
float gLevelScale = 1.0, gLevelOffset = 0.0;
ivec3 gDims = ivec3(1);

ivec3 brickOf(vec3 p) {
    return min(ivec3(p * uInvBrickSize), uBricksPerAxis - 1);
}

void enterBrick(ivec3 b) {
    if (b != gBrick) {
        gBrick = b;
        // One fetch: a second one (the box apart) cost 7 % of the llvmpipe frame.
        uvec4 e = texelFetch(uPageEntry, b, 0);
        ivec3 slot = ivec3(int(e.x << 16u), int(e.x), int(e.y << 16u)) >> 16;
        gState = int(e.y >> 16u) & 3;
        gSlotBase = vec3(slot);
        vec3 first = vec3(b * uBrickSize);
        gBoxLo = first + vec3((uvec3(e.z) >> uvec3(0u, 10u, 20u)) & 1023u);
        gBoxHi = first + vec3((uvec3(e.w) >> uvec3(0u, 10u, 20u)) & 1023u);
        if (!kOneLevel) {
            int level = int(e.y >> 18u);
            gLevelScale = exp2(-float(level));
            gLevelOffset = 0.5 * (gLevelScale - 1.0);
            gDims = uLevelDims[level];
        }
    }
}

// Whether the current brick holds what a sample at p reads. Positions a
// rounding error outside the volume read its edge (clampToVolume).
bool backed(vec3 p) {
    p = clamp(p, vec3(0.0), vec3(uLevelDims[0] - 1));
    return gState != 0 && all(greaterThanEqual(p, gBoxLo)) && all(lessThan(p, gBoxHi));
}

// The current brick's level position of level-0 p.
vec3 toLevel(vec3 p) {
    return kOneLevel ? p : p * gLevelScale + gLevelOffset;
}

// --- filters (positions q in the current brick's level, inside its box's reach)

// The gradient read with the last value, where they share the pool's texels.
vec3 gPoolGradient = vec3(0.0);

float poolValue(vec4 texel) {
    if (kGradientInPool) {
        gPoolGradient = texel.xyz;
        return texel.a * uValueScale;
    }
    return texel.r * uValueScale;
}

float fetchTexel(ivec3 v) {
    return poolValue(texelFetch(uPool, ivec3(gSlotBase) + v, 0));
}

float linearAt(vec3 q) {
    return poolValue(texture(uPool, (gSlotBase + q + 0.5) * uInvPoolSize));
}

vec3 clampToVolume(vec3 q) {
    return clamp(q, vec3(0.0), vec3(gDims - 1));
}

// Cubic B-spline weights folded into two linear fetches per axis (Sigg &
// Hadwiger, GPU Gems 2 ch. 20): g = weights of the pairs, h = where to fetch.
void cubicAxis(float x, out vec2 g, out vec2 h, out vec2 dg, out vec2 dh) {
    float i = floor(x), t = x - i;
    float t2 = t * t, t3 = t2 * t, s = 1.0 - t;
    float w0 = s * s * s / 6.0, w1 = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
    float w2 = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0, w3 = t3 / 6.0;
    float d0 = -s * s / 2.0, d1 = (3.0 * t2 - 4.0 * t) / 2.0;
    float d2 = (-3.0 * t2 + 2.0 * t + 1.0) / 2.0, d3 = t2 / 2.0;
    g = vec2(w0 + w1, w2 + w3);
    h = vec2(i - 1.0 + w1 / g.x, i + 1.0 + w3 / g.y);
    dg = vec2(d0 + d1, d2 + d3);
    dh = vec2(i - 1.0 + d1 / dg.x, i + 1.0 + d3 / dg.y);
}

float cubicSum(vec2 gx, vec2 hx, vec2 gy, vec2 hy, vec2 gz, vec2 hz) {
    float v = 0.0;
    for (int c = 0; c < 2; ++c) {
        for (int b = 0; b < 2; ++b) {
            float wyz = gy[b] * gz[c];
            v += wyz * (gx.x * linearAt(vec3(hx.x, hy[b], hz[c])) +
                        gx.y * linearAt(vec3(hx.y, hy[b], hz[c])));
        }
    }
    return v;
}

float cubicValue(vec3 q, out vec3 grad, bool withGradient) {
    q = clampToVolume(q);
    vec2 gx, hx, dgx, dhx, gy, hy, dgy, dhy, gz, hz, dgz, dhz;
    cubicAxis(q.x, gx, hx, dgx, dhx);
    cubicAxis(q.y, gy, hy, dgy, dhy);
    cubicAxis(q.z, gz, hz, dgz, dhz);
    if (withGradient) {
        grad = vec3(cubicSum(dgx, dhx, gy, hy, gz, hz), cubicSum(gx, hx, dgy, dhy, gz, hz),
                    cubicSum(gx, hx, gy, hy, dgz, dhz));
    }
    return cubicSum(gx, hx, gy, hy, gz, hz);
}

float valueAtLevel(vec3 q) { // any position: clamped to the volume
    if (kInterp == kNearest) {
        return fetchTexel(ivec3(clampToVolume(q) + 0.5));
    }
    if (kInterp == kLinear) {
        return linearAt(clampToVolume(q));
    }
    vec3 unused;
    return cubicValue(q, unused, false);
}

// The gradient per level voxel at level position q (differences, or the spline's).
vec3 levelGradient(vec3 q) {
    if (kInterp == kNearest) {
        ivec3 v = ivec3(clampToVolume(q) + 0.5), hi = gDims - 1;
        return 0.5 * vec3(fetchTexel(min(v + ivec3(1, 0, 0), hi)) - fetchTexel(max(v - ivec3(1, 0, 0), 0)),
                          fetchTexel(min(v + ivec3(0, 1, 0), hi)) - fetchTexel(max(v - ivec3(0, 1, 0), 0)),
                          fetchTexel(min(v + ivec3(0, 0, 1), hi)) - fetchTexel(max(v - ivec3(0, 0, 1), 0)));
    }
    if (kInterp == kLinear) {
        return 0.5 * vec3(valueAtLevel(q + vec3(1, 0, 0)) - valueAtLevel(q - vec3(1, 0, 0)),
                          valueAtLevel(q + vec3(0, 1, 0)) - valueAtLevel(q - vec3(0, 1, 0)),
                          valueAtLevel(q + vec3(0, 0, 1)) - valueAtLevel(q - vec3(0, 0, 1)));
    }
    vec3 grad;
    cubicValue(q, grad, true);
    return grad;
}

// Level-0 p in the current brick.
float valueAt(vec3 p) {
    return valueAtLevel(toLevel(p));
}

vec3 decodeGradient(vec3 texel) {
    return texel * (uGradientScale * gLevelScale);
}

// The gradient per level-0 voxel at level-0 p in the current brick.
vec3 gradientAt(vec3 p) {
    vec3 q = toLevel(p);
    if (kGradientTexture && kInterp == kNearest) {
        return decodeGradient(
            texelFetch(uGradientPool, ivec3(gSlotBase) + ivec3(clampToVolume(q) + 0.5), 0).xyz);
    }
    if (kGradientTexture && kInterp == kLinear) {
        return decodeGradient(
            texture(uGradientPool, (gSlotBase + clampToVolume(q) + 0.5) * uInvPoolSize).xyz);
    }
    return levelGradient(q) * gLevelScale;
}

// --- transfer function --------------------------------------------------------

vec4 classify(float v, int row) {
    float x = clamp((v - uTableLo) * uTableScale, 0.0, float(uTableSize - 1));
    // One linearly filtered fetch between the two entries around x.
    return texture(uTable, vec2((x + 0.5) / float(uTableSize), (float(row) + 0.5) * 0.5));
}

float correctedAlpha(float a, float stepRatio) {
    return a <= 0.0 ? 0.0 : 1.0 - pow(1.0 - min(a, 1.0), stepRatio);
}

uniform float uStepRatio;

// A voxel's value: the texel, or for the spline the spline there (which
// interpolates the voxels).
float voxelValue(ivec3 v) {
    if (kInterp != kCubic) {
        return fetchTexel(v);
    }
    vec3 unused;
    return cubicValue(vec3(v), unused, false);
}

// Pre-classification: the eight voxels classified, then interpolated.
vec4 preclassified(vec3 p) {
    vec3 q = clampToVolume(toLevel(p));
    ivec3 base = ivec3(floor(q));
    vec3 f = q - vec3(base);
    vec4 acc = vec4(0.0);
    for (int n = 0; n < 8; ++n) {
        ivec3 o = ivec3(n & 1, (n >> 1) & 1, (n >> 2) & 1);
        float w = (o.x != 0 ? f.x : 1.0 - f.x) * (o.y != 0 ? f.y : 1.0 - f.y) *
                        (o.z != 0 ? f.z : 1.0 - f.z);
        if (w == 0.0) {
            continue;
        }
        vec4 k = classify(voxelValue(min(base + o, gDims - 1)), 1);
        acc += w * vec4(k.rgb * k.a, k.a);
    }
    if (acc.a <= 0.0) {
        return vec4(0.0);
    }
    return vec4(acc.rgb / acc.a, correctedAlpha(acc.a, uStepRatio));
}

vec2 preTablePosition(float v) {
    float t = (v - uPreLo) / (uPreHi - uPreLo) * float(uPreSize - 1);
    if (!(t > 0.0)) {
        return vec2(0.0);
    }
    if (t >= float(uPreSize - 1)) {
        return vec2(uPreSize - 2, 1.0);
    }
    return vec2(floor(t), t - floor(t));
}

vec4 preintegrated(float front, float back) {
    vec2 f = preTablePosition(front), b = preTablePosition(back);
    ivec2 i = ivec2(f.x, b.x);
    vec4 near = mix(texelFetch(uPreTable, i, 0), texelFetch(uPreTable, i + ivec2(1, 0), 0), f.y);
    vec4 far = mix(texelFetch(uPreTable, i + ivec2(0, 1), 0),
                         texelFetch(uPreTable, i + ivec2(1, 1), 0), f.y);
    return mix(near, far, b.y);
}

// ndotl^power. An integer power (1..64, the presets' 10 among them) is a
// compile-time constant multiplied out by squaring: llvmpipe's pow is a long
// polynomial in every lane.
float specularTerm(float ndotl) {
    if (LUCENT_SPECULAR_INT > 0) {
        float result = 1.0, x = ndotl;
        for (int e = LUCENT_SPECULAR_INT; e > 0; e >>= 1) {
            if ((e & 1) != 0) {
                result *= x;
            }
            x *= x;
        }
        return result;
    }
    return pow(ndotl, uLight.w);
}

vec3 shadeWith(vec3 base, vec3 gradient, vec3 w) {
    vec3 g = uGradientToWorld * gradient;
    float len = length(g);
    if (len < 1e-6) {
        return base;
    }
    float ndotl = min(1.0, abs(dot(g, w)) / len);
    float diffuse = uLight.x + uLight.y * ndotl;
    return base * diffuse + vec3(uLight.z * specularTerm(ndotl));
}

vec3 shade(vec3 base, vec3 p, vec3 w) {
    return shadeWith(base, gradientAt(p), w);
}

// Shading at p, whose value was the last the pool gave (pre-classification
// reads neighbours after it): the gradient read with it, where it came along.
vec3 shadeLast(vec3 base, vec3 p, vec3 w) {
    return kGradientInPool && !kPreclassify ? shadeWith(base, decodeGradient(gPoolGradient), w)
                                            : shade(base, p, w);
}


// --- leaping ------------------------------------------------------------------
//
// Rays leap over cells of 8^3 voxels and over whole bricks. Cell codes, made
// per render: 2 the brick holding the cell is leapt over (not resident, or
// resident only for its neighbours), 1 the cell is, 0 neither. MIP and MinIP
// decide from the cell's min/max as they go. A leap resumes one lattice sample
// before the exit: never past a sample that counts, and the samples it may
// take in an empty cell add nothing.

uniform usampler3D uCellCode;
uniform sampler3D uCellRange; // r = min, g = max over the cell and its overlap
uniform int uCellSize;
uniform float uInvCellSize;
uniform ivec3 uCellsPerAxis;
// Distance maps (render/LeapTextures.h): per cell, its code | r << 2, r the
// reach of the cube of leapt cells within r of it; per block of 2^3 voxels, 0 where a sample may
// show, else 1 + the reach of the cube of blocks around it that show nothing.
uniform usampler3D uCellReach;
uniform usampler3D uBlockReach;
uniform ivec3 uBlocksPerAxis;

vec3 gEntry, gStride; // the ray in level-0 index space: p(n) = gEntry + gStride * n
// Per axis 1 / gStride, 0 where the ray does not move along it; gBound picks
// the box face it leaves by (1: hi, 0: lo). Set with the ray.
vec3 gInvStride, gBound;

void setRayLattice(vec3 entry, vec3 stride) {
    if (kOneLevel) {
        gDims = uLevelDims[0];
    }
    gEntry = entry;
    gStride = stride;
    bvec3 moving = greaterThan(abs(stride), vec3(1e-20));
    gInvStride = mix(vec3(0.0), 1.0 / stride, moving);
    gBound = vec3(greaterThan(stride, vec3(0.0)));
}

// The lattice index at which the ray leaves the box [lo, hi): a product per
// axis, no division (every lane of llvmpipe runs this for every sample).
float exitIndex(vec3 lo, vec3 hi) {
    vec3 t = (mix(lo, hi, gBound) - gEntry) * gInvStride;
    t = mix(vec3(1.0e30), t, notEqual(gInvStride, vec3(0.0)));
    return min(t.x, min(t.y, t.z));
}

// --- the overlay ------------------------------------------------------------------

float overlayValue(vec3 p) {
    return texture(uOverlay, (p + 0.5) * uOverlayInvDims).r;
}

// The overlay's entry for v in the table's row (0: opacity corrected, 1: raw);
// transparent for NaN (no overlay there).
vec4 overlayEntry(float v, int row) {
    if (isnan(v)) {
        return vec4(0.0);
    }
    // windowToGrey's lround: halves away from zero (below 0 clamps to 0 anyway).
    float x = floor((v - uOverlayLow) / uOverlayWidth * 255.0 + 0.5);
    return texelFetch(uOverlayTable, ivec2(int(clamp(x, 0.0, 255.0)), row), 0);
}

// The base's sample k (colour, opacity) and the overlay's o mixed: the opacities
// combined, the colours weighted by opacity; o.a = 0 leaves k.
vec4 fuse(vec4 k, vec4 o) {
    if (!(o.a > 0.0)) {
        return k;
    }
    float ab = max(k.a, 0.0), sum = ab + o.a;
    return vec4((ab * k.rgb + o.a * o.rgb) / sum, ab + o.a - ab * o.a);
}
