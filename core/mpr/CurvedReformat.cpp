#include "core/mpr/CurvedReformat.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace lucent {
namespace {

constexpr float kOutside = std::numeric_limits<float>::quiet_NaN();

// Barry and Goldman's pyramid for the centripetal Catmull-Rom segment P1..P2.
glm::dvec3 catmullRom(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2,
                      const glm::dvec3& p3, double u) {
    const auto knot = [](double t, const glm::dvec3& a, const glm::dvec3& b) {
        return t + std::sqrt(std::max(glm::distance(a, b), 1e-9)); // alpha = 0.5
    };
    const double t0 = 0.0, t1 = knot(t0, p0, p1), t2 = knot(t1, p1, p2), t3 = knot(t2, p2, p3);
    const double t = t1 + u * (t2 - t1);
    const auto mix = [t](const glm::dvec3& a, const glm::dvec3& b, double ta, double tb) {
        return (tb - t) / (tb - ta) * a + (t - ta) / (tb - ta) * b;
    };
    const glm::dvec3 a1 = mix(p0, p1, t0, t1), a2 = mix(p1, p2, t1, t2), a3 = mix(p2, p3, t2, t3);
    const glm::dvec3 b1 = mix(a1, a2, t0, t2), b2 = mix(a2, a3, t1, t3);
    return mix(b1, b2, t1, t2);
}

// Any unit vector perpendicular to t, preferring the part of `up` across t.
glm::dvec3 perpendicular(const glm::dvec3& t, const glm::dvec3& up) {
    glm::dvec3 r = up - glm::dot(up, t) * t;
    if (glm::length(r) < 1e-6) {
        const glm::dvec3 axis = std::abs(t.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        r = axis - glm::dot(axis, t) * t;
    }
    return glm::normalize(r);
}

// The samples of one pixel across the cut surface along `across`, combined.
float samplePixel(const Volume& volume, const glm::dvec3& p, const glm::dvec3& across,
                  const CurvedOptions& o) {
    const VolumeGeometry& g = volume.geometry();
    if (o.slabThickness <= 0.0) {
        return static_cast<float>(sampleAt(volume, g.toIndex(p)));
    }
    const int steps = std::max(1, int(std::ceil(o.slabThickness / sliceStep(g, across))));
    double best = o.slabMode == SlabMode::Mip ? -1e300 : 1e300, sum = 0.0;
    int inside = 0;
    for (int k = 0; k <= steps; ++k) {
        const double d = -0.5 * o.slabThickness + o.slabThickness * k / steps;
        const double v = sampleAt(volume, g.toIndex(p + across * d));
        if (std::isnan(v)) {
            continue;
        }
        ++inside;
        sum += v;
        best = o.slabMode == SlabMode::Mip ? std::max(best, v) : std::min(best, v);
    }
    if (inside == 0) {
        return kOutside;
    }
    return static_cast<float>(o.slabMode == SlabMode::Average ? sum / inside : best);
}

void checkPixelSize(const CurvedOptions& o) {
    if (!(o.pixelSize > 0.0) || !(o.halfWidth >= 0.0)) {
        throw std::invalid_argument("curved reformation: the pixel size must be positive and "
                                    "the half width not negative");
    }
}

} // namespace

glm::dvec3 Centerline::pointAt(double s) const {
    const double f = std::clamp(s / step, 0.0, double(points.size() - 1));
    const std::size_t i = std::min(std::size_t(f), points.size() - 2);
    return glm::mix(points[i], points[i + 1], f - double(i));
}

glm::dvec3 Centerline::tangentAt(double s) const {
    const double f = std::clamp(s / step, 0.0, double(points.size() - 1));
    const std::size_t i = std::min(std::size_t(f), points.size() - 2);
    return glm::normalize(glm::mix(tangents[i], tangents[i + 1], f - double(i)));
}

glm::dvec3 Centerline::normalAt(double s) const {
    const double f = std::clamp(s / step, 0.0, double(points.size() - 1));
    const std::size_t i = std::min(std::size_t(f), points.size() - 2);
    return perpendicular(tangentAt(s), glm::mix(normals[i], normals[i + 1], f - double(i)));
}

Centerline centerlineThrough(const std::vector<glm::dvec3>& controls, double step,
                             const glm::dvec3& up) {
    std::vector<glm::dvec3> p;
    for (const glm::dvec3& c : controls) {
        if (p.empty() || glm::distance(p.back(), c) > 1e-6) {
            p.push_back(c);
        }
    }
    if (p.size() < 2 || !(step > 0.0)) {
        throw std::invalid_argument("a curved path needs two or more distinct points and a "
                                    "positive step");
    }
    // A dense polyline along the spline; the ends continue straight.
    std::vector<glm::dvec3> dense{p.front()};
    const std::size_t n = p.size();
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const glm::dvec3 p0 = i == 0 ? 2.0 * p[0] - p[1] : p[i - 1];
        const glm::dvec3 p3 = i + 2 >= n ? 2.0 * p[n - 1] - p[n - 2] : p[i + 2];
        const int pieces = std::max(8, int(std::ceil(glm::distance(p[i], p[i + 1]) * 8.0 / step)));
        for (int k = 1; k <= pieces; ++k) {
            dense.push_back(catmullRom(p0, p[i], p[i + 1], p3, double(k) / pieces));
        }
    }
    std::vector<double> arc{0.0};
    for (std::size_t i = 1; i < dense.size(); ++i) {
        arc.push_back(arc.back() + glm::distance(dense[i - 1], dense[i]));
    }
    Centerline c;
    const int intervals = std::max(1, int(std::ceil(arc.back() / step)));
    c.step = arc.back() / intervals;
    std::size_t j = 0;
    for (int k = 0; k <= intervals; ++k) {
        const double s = std::min(k * c.step, arc.back());
        while (j + 2 < arc.size() && arc[j + 1] < s) {
            ++j;
        }
        const double f = (s - arc[j]) / std::max(arc[j + 1] - arc[j], 1e-12);
        c.points.push_back(glm::mix(dense[j], dense[j + 1], std::clamp(f, 0.0, 1.0)));
    }
    const std::size_t m = c.points.size();
    for (std::size_t i = 0; i < m; ++i) {
        const glm::dvec3 d = c.points[std::min(i + 1, m - 1)] - c.points[i == 0 ? 0 : i - 1];
        c.tangents.push_back(glm::normalize(d));
    }
    // Double reflection: each normal is the last one carried along without twist.
    c.normals.push_back(perpendicular(c.tangents[0], up));
    for (std::size_t i = 0; i + 1 < m; ++i) {
        const glm::dvec3 v1 = c.points[i + 1] - c.points[i];
        const double c1 = glm::dot(v1, v1);
        const glm::dvec3 rL = c.normals[i] - (2.0 / c1) * glm::dot(v1, c.normals[i]) * v1;
        const glm::dvec3 tL = c.tangents[i] - (2.0 / c1) * glm::dot(v1, c.tangents[i]) * v1;
        const glm::dvec3 v2 = c.tangents[i + 1] - tL;
        const double c2 = glm::dot(v2, v2);
        const glm::dvec3 r = c2 < 1e-20 ? rL : rL - (2.0 / c2) * glm::dot(v2, rL) * v2;
        c.normals.push_back(perpendicular(c.tangents[i + 1], r));
    }
    return c;
}

CurvedImage straightenedReformat(const Volume& volume, const Centerline& path,
                                 const CurvedOptions& o) {
    checkPixelSize(o);
    CurvedImage image;
    image.pixelSize = o.pixelSize;
    image.height = int(std::floor(path.length() / o.pixelSize)) + 1;
    const int half = int(std::lround(o.halfWidth / o.pixelSize));
    image.width = 2 * half + 1;
    image.pixels.resize(std::size_t(image.width) * image.height);
    const double turn = glm::radians(o.rotationDeg);
    for (int y = 0; y < image.height; ++y) {
        const double s = y * o.pixelSize;
        const glm::dvec3 t = path.tangentAt(s);
        const glm::dvec3 n = path.normalAt(s);
        const glm::dvec3 across = std::cos(turn) * n + std::sin(turn) * glm::cross(t, n);
        const glm::dvec3 slab = glm::cross(t, across);
        image.rowOrigin.push_back(path.pointAt(s) - across * (half * o.pixelSize));
        image.rowDirection.push_back(across);
        image.pathColumn.push_back(half);
        image.rowArc.push_back(s);
        for (int x = 0; x < image.width; ++x) {
            image.pixels[std::size_t(y) * image.width + x] =
                samplePixel(volume, image.pointAt(x, y), slab, o);
        }
    }
    return image;
}

CurvedImage stretchedReformat(const Volume& volume, const Centerline& path, const glm::dvec3& up,
                              const CurvedOptions& o) {
    checkPixelSize(o);
    const glm::dvec3 v = glm::normalize(up);
    const std::size_t m = path.points.size();
    // The path seen along v, and its arc length: the rows' coordinate.
    std::vector<double> seen{0.0};
    double low = 1e300, high = -1e300;
    for (std::size_t i = 0; i < m; ++i) {
        const double h = glm::dot(path.points[i], v);
        low = std::min(low, h);
        high = std::max(high, h);
        if (i > 0) {
            const glm::dvec3 d = path.points[i] - path.points[i - 1];
            seen.push_back(seen.back() + glm::length(d - glm::dot(d, v) * v));
        }
    }
    if (seen.back() < o.pixelSize) {
        throw std::invalid_argument("the path runs along the up direction: a stretched "
                                    "reformation along it has no length");
    }
    CurvedImage image;
    image.pixelSize = o.pixelSize;
    image.height = int(std::floor(seen.back() / o.pixelSize)) + 1;
    const double h0 = low - o.halfWidth;
    image.width = int(std::ceil((high + o.halfWidth - h0) / o.pixelSize)) + 1;
    image.pixels.resize(std::size_t(image.width) * image.height);
    std::size_t i = 0;
    for (int y = 0; y < image.height; ++y) {
        const double s = y * o.pixelSize;
        while (i + 2 < m && seen[i + 1] < s) {
            ++i;
        }
        const double f =
            std::clamp((s - seen[i]) / std::max(seen[i + 1] - seen[i], 1e-12), 0.0, 1.0);
        const glm::dvec3 c = glm::mix(path.points[i], path.points[i + 1], f);
        const glm::dvec3 d = path.points[i + 1] - path.points[i];
        const glm::dvec3 along = d - glm::dot(d, v) * v;
        const glm::dvec3 slab = glm::normalize(glm::cross(v, along));
        image.rowOrigin.push_back(c + (h0 - glm::dot(c, v)) * v);
        image.rowDirection.push_back(v);
        image.pathColumn.push_back((glm::dot(c, v) - h0) / o.pixelSize);
        image.rowArc.push_back((double(i) + f) * path.step);
        for (int x = 0; x < image.width; ++x) {
            image.pixels[std::size_t(y) * image.width + x] =
                samplePixel(volume, image.pointAt(x, y), slab, o);
        }
    }
    return image;
}

SlicePlane crossSection(const Centerline& path, double s, int size, double pixelSize) {
    SlicePlane plane;
    plane.centre = path.pointAt(s);
    plane.u = path.normalAt(s);
    plane.v = glm::cross(path.tangentAt(s), plane.u); // u x v = tangent: looking along the path
    plane.width = plane.height = size;
    plane.pixelSize = pixelSize;
    return plane;
}

} // namespace lucent
