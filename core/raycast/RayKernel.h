#pragma once
// The per-ray work of the CPU ray caster, templated on precision and filter.
// Private to core/raycast.

#include <cmath>
#include <limits>
#include <vector>

#include "core/raycast/OverlaySampler.h"
#include "core/raycast/RaySetup.h"
#include "core/raycast/VolumeFields.h"

namespace lucent {

// Overlay: NoOverlay, or OverlaySampler<Real> for a fused render (OverlaySampler.h has the
// mixing rule; the setup leaps only where the overlay shows nothing either, OverlayLeaping.h,
// and not at all in MIP, MinIP and average). Without an overlay the kernel is the plain one:
// every overlay branch is constexpr.
template <class Real, class Field, class Overlay = NoOverlay> class RayKernel {
    static constexpr long kPrefetchAhead = 16;

public:
    RayKernel(const RaySetup<Real>& s, const Field& f, const Overlay& overlay = {})
        : s_(s), f_(f), overlay_(overlay) {}

    // o, d: ray origin and direction per mm of patient distance, in index space;
    // w: the unit ray direction in patient space.
    RayOutput cast(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& w) const;

private:
    struct Rgba {
        Real r, g, b, a; // r, g, b not premultiplied
    };

    // Alpha per dt_ref (raw) or already corrected for dt (the float table path only).
    Rgba classifyValue(double v, bool raw) const;
    Rgba sampleColour(const Vec3<Real>& p, Real value) const; // alpha corrected for dt
    Real corrected(Real a) const {
        return a <= Real(0)
                   ? Real(0)
                   : Real(1) - std::pow(Real(1) - std::min(a, Real(1)), Real(s_.stepRatio));
    }
    Vec3<Real> shade(const Vec3<Real>& base, const Vec3<Real>& p, const glm::dvec3& w) const;
    static int cellOf(const typename RaySetup<Real>::LeapLevel& l, const Vec3<Real>& p);
    static double cellExit(const typename RaySetup<Real>::LeapLevel& l, int cell,
                           const glm::dvec3& o, const glm::dvec3& d, double t);
    bool skippable(const typename RaySetup<Real>::LeapLevel& l, int cell, bool havePrev,
                   Real extreme) const;
    // DVR with an overlay: the base's classified, shaded sample at p mixed with the
    // overlay's there (alpha 0: nothing). Keeps the pre-integration segment in prev.
    Rgba fusedSample(const Vec3<Real>& p, Real v, const glm::dvec3& w, bool& havePrev,
                     Real& prev) const;
    // A projection's premultiplied colour with the overlay's maximum drawn over it.
    glm::dvec4 overProjection(const glm::dvec4& base, Real overlayMax) const;

    const RaySetup<Real>& s_;
    const Field& f_;
    [[no_unique_address]] Overlay overlay_;
};

template <class Real, class Field, class Overlay>
typename RayKernel<Real, Field, Overlay>::Rgba
RayKernel<Real, Field, Overlay>::fusedSample(const Vec3<Real>& p, Real v, const glm::dvec3& w,
                                             bool& havePrev, Real& prev) const {
    Rgba c{0, 0, 0, 0};
    if (s_.preintegrate) {
        if (havePrev) {
            const glm::dvec4 seg = s_.exactSegments
                                       ? (*s_.exactSegments)(double(prev), double(v))
                                       : glm::dvec4(s_.preTable->lookup(double(prev), double(v)));
            if (seg.a > 0.0) {
                c = {Real(seg.r / seg.a), Real(seg.g / seg.a), Real(seg.b / seg.a), Real(seg.a)};
            }
        }
        prev = v;
        havePrev = true; // the first sample opens the first segment
    } else if (s_.classification != Classification::Post ||
               (double(v) >= s_.visibleLo && double(v) <= s_.visibleHi)) {
        c = sampleColour(p, v);
    }
    if (c.a > Real(0) && s_.shading) {
        const Vec3<Real> rgb = shade(Vec3<Real>(c.r, c.g, c.b), p, w);
        c = {rgb.r, rgb.g, rgb.b, c.a};
    }
    if constexpr (Overlay::kEnabled) {
        const OverlayEntry* e = overlay_.entry(overlay_.value(p));
        if (e == nullptr || !(e->alpha > 0.0f)) {
            return c;
        }
        const Real ao = Real(e->alpha), ab = c.a > Real(0) ? c.a : Real(0);
        const Real sum = ab + ao;
        return {(ab * c.r + ao * Real(e->colour.r)) / sum,
                (ab * c.g + ao * Real(e->colour.g)) / sum,
                (ab * c.b + ao * Real(e->colour.b)) / sum, ab + ao - ab * ao};
    }
    return c;
}

template <class Real, class Field, class Overlay>
glm::dvec4 RayKernel<Real, Field, Overlay>::overProjection(const glm::dvec4& base,
                                                           Real overlayMax) const {
    if constexpr (Overlay::kEnabled) {
        const OverlayEntry* e = overlay_.entry(overlayMax);
        if (e != nullptr && e->rawAlpha > 0.0f) {
            const double a = double(e->rawAlpha);
            return base * (1.0 - a) + glm::dvec4(glm::dvec3(e->colour) * a, a);
        }
    }
    (void)overlayMax;
    return base;
}

template <class Real, class Field, class Overlay>
typename RayKernel<Real, Field, Overlay>::Rgba
RayKernel<Real, Field, Overlay>::classifyValue(double v, bool raw) const {
    if (s_.exactTf) {
        const glm::dvec3 c = s_.tf->colourAt(v);
        const Real a = Real(s_.tf->opacityAt(v));
        return {Real(c.r), Real(c.g), Real(c.b), raw ? a : corrected(a)};
    }
    const std::vector<glm::vec4>& t = raw ? *s_.rawTable : *s_.table;
    const float x = std::clamp(float((v - s_.tableLo) * s_.tableScale), 0.0f, float(t.size() - 1));
    const std::size_t i = std::min(static_cast<std::size_t>(x), t.size() - 2);
    const float f = x - float(i);
    const glm::vec4 c = t[i] + f * (t[i + 1] - t[i]);
    return {Real(c.r), Real(c.g), Real(c.b), Real(c.a)};
}

template <class Real, class Field, class Overlay>
typename RayKernel<Real, Field, Overlay>::Rgba
RayKernel<Real, Field, Overlay>::sampleColour(const Vec3<Real>& p, Real value) const {
    if (s_.classification == Classification::Post || Field::isNearest) {
        return classifyValue(double(value), false);
    }
    // Pre-classification (trilinear): classify the eight voxels, interpolate
    // their premultiplied colour and opacity, then correct the opacity for dt.
    const Vec3<Real> q = glm::clamp(p, Vec3<Real>(s_.boxLo), Vec3<Real>(s_.boxHi));
    const glm::ivec3 base(glm::floor(q));
    const Vec3<Real> frac = q - Vec3<Real>(base);
    Real r = 0, g = 0, b = 0, a = 0;
    for (int n = 0; n < 8; ++n) {
        const glm::ivec3 o(n & 1, (n >> 1) & 1, (n >> 2) & 1);
        const Real wgt =
            (o.x ? frac.x : 1 - frac.x) * (o.y ? frac.y : 1 - frac.y) * (o.z ? frac.z : 1 - frac.z);
        if (wgt == Real(0)) {
            continue;
        }
        const glm::ivec3 v = glm::min(base + o, glm::ivec3(s_.boxHi));
        const Rgba k = classifyValue(double(f_.value(Vec3<Real>(v))), true);
        r += wgt * k.r * k.a;
        g += wgt * k.g * k.a;
        b += wgt * k.b * k.a;
        a += wgt * k.a;
    }
    if (a <= Real(0)) {
        return {0, 0, 0, 0};
    }
    return {r / a, g / a, b / a, corrected(a)};
}

template <class Real, class Field, class Overlay>
Vec3<Real> RayKernel<Real, Field, Overlay>::shade(const Vec3<Real>& base, const Vec3<Real>& p,
                                                  const glm::dvec3& w) const {
    const Vec3<Real> g = glm::mat<3, 3, Real>(s_.gradientToWorld) * f_.gradient(p);
    const Real len = glm::length(g);
    if (len < Real(1e-6)) {
        return base; // no surface to light: a homogeneous region keeps its colour
    }
    // Headlight: the light comes from the eye, so L = V = H = -w; two-sided.
    const Real ndotl = std::min(Real(1), std::abs(glm::dot(g, Vec3<Real>(w))) / len);
    const Real diffuse = Real(s_.light.ambient) + Real(s_.light.diffuse) * ndotl;
    const Real specular = Real(s_.light.specular) * std::pow(ndotl, Real(s_.light.specularPower));
    return base * diffuse + Vec3<Real>(specular);
}

template <class Real, class Field, class Overlay>
int RayKernel<Real, Field, Overlay>::cellOf(const typename RaySetup<Real>::LeapLevel& l,
                                            const Vec3<Real>& p) {
    // Samples lie inside the box (p >= 0 up to rounding): truncation is floor.
    const glm::ivec3 b = glm::min(glm::ivec3(p * l.inverseSize), l.perAxis - 1);
    return b.x + l.perAxis.x * (b.y + l.perAxis.y * b.z);
}

template <class Real, class Field, class Overlay>
double RayKernel<Real, Field, Overlay>::cellExit(const typename RaySetup<Real>::LeapLevel& l,
                                                 int cell, const glm::dvec3& o, const glm::dvec3& d,
                                                 double t) {
    const glm::ivec3 n = l.perAxis;
    const glm::ivec3 idx(cell % n.x, (cell / n.x) % n.y, cell / (n.x * n.y));
    return leapCellExit(l.size, n, idx, o, d, t);
}

template <class Real, class Field, class Overlay>
bool RayKernel<Real, Field, Overlay>::skippable(const typename RaySetup<Real>::LeapLevel& l,
                                                int cell, bool havePrev, Real extreme) const {
    switch (s_.mode) {
    case RenderMode::Mip:
        return havePrev && (*l.range)[cell].y <= float(extreme);
    case RenderMode::MinIp:
        return havePrev && (*l.range)[cell].x >= float(extreme);
    case RenderMode::Average:
        return false;
    case RenderMode::Dvr:
    case RenderMode::Isosurface:
        break;
    }
    return (*l.skippable)[cell] != 0;
}

template <class Real, class Field, class Overlay>
RayOutput RayKernel<Real, Field, Overlay>::cast(const glm::dvec3& o, const glm::dvec3& d,
                                                const glm::dvec3& w) const {
    RayOutput out;
    RaySpan span;
    if (!raySpan(s_, o, d, span)) {
        return out;
    }
    const double t0 = span.t0, dt = s_.dt;
    const bool continuity = s_.preintegrate || s_.mode == RenderMode::Isosurface;
    const long nFirst =
        continuity && previousSampleShared(s_, o, d, span) ? span.nFirst - 1 : span.nFirst;
    const long nLast = span.nLast;

    Real accR = 0, accG = 0, accB = 0, accA = 0;
    Real extreme = s_.mode == RenderMode::MinIp ? std::numeric_limits<Real>::max()
                                                : std::numeric_limits<Real>::lowest();
    double sum = 0.0;
    long count = 0;
    bool havePrev = false;
    Real prev = 0;
    double tPrev = 0.0;
    Real overlayMax = std::numeric_limits<Real>::quiet_NaN(); // NaN: no overlay value yet
    int checkedCell = -1;
    auto position = [&](double t) { return Vec3<Real>(o + d * t); };
    // Lattice samples: one formula for every path, so leaping never moves a sample.
    const Vec3<Real> entry(o + d * t0), stride(d * dt);
    auto lattice = [&](long n) { return entry + stride * Real(n); };

    for (long n = nFirst; n <= nLast; ++n) {
        const double t = t0 + double(n) * dt;
        const Vec3<Real> p = lattice(n);
        if (s_.leap) {
            const int fine = cellOf(s_.levels[1], p);
            if (fine != checkedCell) {
                checkedCell = fine;
                // The brick first (one leap covers it all), then the cell.
                const int coarse = cellOf(s_.levels[0], p);
                double exit = -1.0;
                if (skippable(s_.levels[0], coarse, havePrev, extreme)) {
                    exit = cellExit(s_.levels[0], coarse, o, d, t);
                } else if (skippable(s_.levels[1], fine, havePrev, extreme)) {
                    exit = cellExit(s_.levels[1], fine, o, d, t);
                }
                if (exit >= 0.0) {
                    // Resume at the last lattice sample not beyond the exit: it may
                    // still lie inside (then it is taken, harmlessly), never past a sample that
                    // counts.
                    const long resume = std::max(n + 1, long(std::floor((exit - t0) / dt)));
                    if (!continuity) {
                        n = resume - 1;
                        continue;
                    }
                    // Iso and pre-integration need the samples on both sides of the
                    // leap: sample n is taken below, and the last one before `resume`
                    // becomes the previous sample of the one we resume at.
                    const Real vn = f_.value(p);
                    ++out.samples;
                    const bool crossing = s_.mode == RenderMode::Isosurface && havePrev &&
                                          (prev < Real(s_.isoValue)) != (vn < Real(s_.isoValue));
                    if (!crossing && resume - 1 > n) {
                        const double tl = t0 + double(resume - 1) * dt;
                        prev = f_.value(lattice(resume - 1));
                        tPrev = tl;
                        havePrev = true;
                        ++out.samples;
                        n = resume - 1;
                        continue;
                    }
                }
            }
        }
        ++out.samples;
        // Volume reads along a ray miss the cache; ask for them well ahead.
        f_.g.prefetch(lattice(n + kPrefetchAhead));
        const Real v = f_.valueInside(p);
        if constexpr (Overlay::kEnabled) {
            if (s_.mode != RenderMode::Dvr) {
                const Real ov = overlay_.value(p);
                overlayMax = std::isnan(overlayMax) || ov > overlayMax ? ov : overlayMax;
            } else {
                const Rgba c = fusedSample(p, v, w, havePrev, prev);
                if (c.a > Real(0)) {
                    const Real weight = (Real(1) - accA) * c.a;
                    accR += weight * c.r;
                    accG += weight * c.g;
                    accB += weight * c.b;
                    accA += weight;
                    if (accA >= s_.earlyTermination) {
                        break;
                    }
                }
                continue;
            }
        }
        switch (s_.mode) {
        case RenderMode::Mip:
            extreme = std::max(extreme, v);
            havePrev = true;
            continue;
        case RenderMode::MinIp:
            extreme = std::min(extreme, v);
            havePrev = true;
            continue;
        case RenderMode::Average:
            sum += double(v);
            ++count;
            continue;
        case RenderMode::Isosurface: {
            const Real iso = Real(s_.isoValue);
            if (havePrev && (prev < iso) != (v < iso)) {
                // Bisection between the two lattice samples for the crossing.
                double a = tPrev, b = t;
                Real va = prev;
                for (int it = 0; it < 40 && b - a > 1e-9 * dt; ++it) {
                    const double m = 0.5 * (a + b);
                    const Real vm = f_.value(position(m));
                    if ((va < iso) == (vm < iso)) {
                        a = m;
                        va = vm;
                    } else {
                        b = m;
                    }
                }
                const Vec3<Real> hit = position(0.5 * (a + b));
                const Rgba c = classifyValue(s_.isoValue, true);
                Vec3<Real> rgb(c.r, c.g, c.b);
                if (s_.shading) {
                    rgb = shade(rgb, hit, w);
                }
                out.rgba = glm::dvec4(glm::dvec3(rgb), 1.0);
                return out;
            }
            prev = v;
            tPrev = t;
            havePrev = true;
            continue;
        }
        case RenderMode::Dvr:
            break;
        }

        Rgba c{0, 0, 0, 0};
        if (s_.preintegrate) {
            if (!havePrev) {
                prev = v;
                havePrev = true;
                continue; // the first sample opens the first segment
            }
            const glm::dvec4 seg = s_.exactSegments
                                       ? (*s_.exactSegments)(double(prev), double(v))
                                       : glm::dvec4(s_.preTable->lookup(double(prev), double(v)));
            prev = v;
            if (seg.a <= 0.0) {
                continue;
            }
            c = {Real(seg.r / seg.a), Real(seg.g / seg.a), Real(seg.b / seg.a), Real(seg.a)};
        } else {
            if (s_.classification == Classification::Post &&
                (double(v) < s_.visibleLo || double(v) > s_.visibleHi)) {
                continue; // transparent: no table lookup, no shading
            }
            c = sampleColour(p, v);
        }
        if (c.a <= Real(0)) {
            continue;
        }
        Vec3<Real> rgb(c.r, c.g, c.b);
        if (s_.shading) {
            rgb = shade(rgb, p, w);
        }
        const Real weight = (Real(1) - accA) * c.a;
        accR += weight * rgb.r;
        accG += weight * rgb.g;
        accB += weight * rgb.b;
        accA += weight;
        if (accA >= s_.earlyTermination) {
            break;
        }
    }

    if (s_.mode == RenderMode::Mip || s_.mode == RenderMode::MinIp ||
        s_.mode == RenderMode::Average) {
        const bool any = s_.mode == RenderMode::Average ? count > 0 : havePrev;
        if (!any) {
            return out;
        }
        const double v = s_.mode == RenderMode::Average ? sum / double(count) : double(extreme);
        out.projection = s_.mode == RenderMode::Average ? glm::dvec2(sum, double(count))
                                                        : glm::dvec2(double(extreme), 1.0);
        const Rgba c = classifyValue(v, true);
        // Projections show the transfer function's colour and opacity of the projected value.
        const double a = double(c.a);
        out.rgba = glm::dvec4(glm::dvec3(c.r, c.g, c.b) * a, a);
        if constexpr (Overlay::kEnabled) {
            out.rgba = overProjection(out.rgba, overlayMax);
        }
        return out;
    }
    out.rgba = glm::dvec4(accR, accG, accB, accA);
    return out;
}

} // namespace lucent
