#include "core/surface/SphereIntegrals.h"

#include <array>
#include <limits>
#include <numbers>

namespace lucent {

namespace {

// Rounds a double to the float on the given side of it.
float floatBelow(double v) {
    const float f = static_cast<float>(v);
    return double(f) > v ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

float floatAbove(double v) {
    const float f = static_cast<float>(v);
    return double(f) < v ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

// The part [s1, s2] of the edge A + s·(B − A), s ∈ [0, 1], that lies inside
// the circle |P|² ≤ r²; s1 = s2 = 1 when none does.
struct EdgeCut {
    double s1 = 1.0, s2 = 1.0;
    bool crosses() const { return s1 < s2; }
};

EdgeCut cutEdge(const glm::dvec3& a, const glm::dvec3& b, double r2) {
    const glm::dvec3 d = b - a;
    const double dd = glm::dot(d, d), ad = glm::dot(a, d), aa = glm::dot(a, a) - r2;
    const double disc = ad * ad - dd * aa;
    if (dd == 0.0 || disc <= 0.0) {
        return {};
    }
    // Roots of dd·s² + 2·ad·s + aa, in the form that does not cancel.
    const double q = -ad - std::copysign(std::sqrt(disc), ad);
    const double r1 = q / dd, r2root = aa / q;
    const double s1 = std::clamp(std::min(r1, r2root), 0.0, 1.0);
    const double s2 = std::clamp(std::max(r1, r2root), 0.0, 1.0);
    return s1 < s2 ? EdgeCut{s1, s2} : EdgeCut{};
}

// Running sums over the fan pieces about the disc centre c (in-plane vectors).
struct FanSums {
    glm::dvec3 n{0.0};
    double h = 0.0;
    HalfAngleSum& straightHalfAngles; // Σ Ω/2 of the straight pieces (c, P, Q) seen from X
    double twiceTriangles = 0.0;      // Σ n·(P×Q) over the straight pieces
    double arcAngle = 0.0;            // Σ θ over the arc pieces

    void arc(const glm::dvec3& p, const glm::dvec3& q) {
        arcAngle += std::atan2(glm::dot(n, glm::cross(p, q)), glm::dot(p, q));
    }

    // Van Oosterom for the triangle (c, P, Q) seen from X = c − h·n, with |h|
    // taken out of numerator and denominator: triple product h·n·(P×Q).
    void straight(const glm::dvec3& p, const glm::dvec3& q) {
        const double cross = glm::dot(n, glm::cross(p, q));
        twiceTriangles += cross;
        if (h == 0.0) {
            return;
        }
        const double ah = std::abs(h);
        const double lp = std::sqrt(h * h + glm::dot(p, p));
        const double lq = std::sqrt(h * h + glm::dot(q, q));
        straightHalfAngles.add(h > 0.0 ? cross : -cross,
                               lp * lq + ah * (lp + lq) + h * h + glm::dot(p, q));
    }
};

// Whether the disc centre (the origin of v) lies inside the triangle v.
bool centreInside(const std::array<glm::dvec3, 3>& v, const glm::dvec3& n) {
    for (int i = 0; i < 3; ++i) {
        if (glm::dot(n, glm::cross(v[i], v[(i + 1) % 3])) < 0.0) {
            return false;
        }
    }
    return true;
}

} // namespace

PreparedTriangle prepareTriangle(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2) {
    PreparedTriangle t;
    t.p0 = p0, t.p1 = p1, t.p2 = p2;
    const glm::dvec3 lo = glm::min(p0, glm::min(p1, p2)), hi = glm::max(p0, glm::max(p1, p2));
    t.boxLo = {floatBelow(lo.x), floatBelow(lo.y), floatBelow(lo.z)};
    t.boxHi = {floatAbove(hi.x), floatAbove(hi.y), floatAbove(hi.z)};
    const glm::dvec3 cross = glm::cross(p1 - p0, p2 - p0);
    const double twiceArea = glm::length(cross);
    if (twiceArea > 0.0 && std::isfinite(twiceArea)) {
        t.area = 0.5 * twiceArea;
        t.normal = cross / twiceArea;
    }
    return t;
}

double triangleSolidAngle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    const double triple = glm::dot(a, glm::cross(b, c));
    if (triple == 0.0) {
        return 0.0; // eye in the triangle's plane, at a vertex, or a degenerate triangle
    }
    const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
    return 2.0 * std::atan2(triple, la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb +
                                        glm::dot(b, c) * la);
}

BallPart clippedPart(const PreparedTriangle& t, const Ball& ball, double h,
                     HalfAngleSum& halfAngles) {
    const glm::dvec3 c = ball.centre + h * t.normal;
    const double r2 = ball.radius2 - h * h;
    const std::array<glm::dvec3, 3> v{t.p0 - c, t.p1 - c, t.p2 - c};
    std::array<EdgeCut, 3> cuts;
    bool anyChord = false;
    for (int i = 0; i < 3; ++i) {
        cuts[i] = cutEdge(v[i], v[(i + 1) % 3], r2);
        anyChord = anyChord || cuts[i].crosses();
    }
    // Signed solid angle of a whole disc of radius r at height |h|: 2π(1 − |h|/R).
    const double discFraction = std::copysign(1.0 - std::abs(h) / ball.radius, h);
    if (!anyChord) {
        // No edge meets the disc: it lies wholly inside T or wholly outside.
        if (!centreInside(v, t.normal)) {
            return {};
        }
        return {std::numbers::pi * r2, h == 0.0 ? 0.0 : 2.0 * std::numbers::pi * discFraction};
    }
    FanSums fan{t.normal, h, halfAngles};
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3& a = v[i];
        const glm::dvec3& b = v[(i + 1) % 3];
        const glm::dvec3 d = b - a;
        const glm::dvec3 in = cuts[i].s1 == 1.0 ? b : a + cuts[i].s1 * d;
        const glm::dvec3 out = cuts[i].s2 == 1.0 ? b : a + cuts[i].s2 * d;
        if (cuts[i].s1 > 0.0) {
            fan.arc(a, in);
        }
        if (cuts[i].crosses()) {
            fan.straight(in, out);
        }
        if (cuts[i].s2 < 1.0) {
            fan.arc(out, b);
        }
    }
    const double area = 0.5 * (fan.twiceTriangles + r2 * fan.arcAngle);
    return {area, h == 0.0 ? 0.0 : discFraction * fan.arcAngle};
}

BallPart clippedPart(const PreparedTriangle& t, const Ball& ball, double h) {
    HalfAngleSum halfAngles;
    BallPart part = clippedPart(t, ball, h, halfAngles);
    part.solidAngle += 2.0 * halfAngles.value();
    return part;
}

BallContribution ballContribution(const PreparedTriangle& t, const Ball& ball) {
    BallSums sums(ball);
    const BallPath path = sums.add(t);
    return {sums.area(), sums.volume(0.0), path};
}

} // namespace lucent
