#pragma once
// Exact integrals of one triangle against a ball B(X, R), the kernels of the
// method of spheres: the area |T∩B| and the triangle's part of the volume of
// the solid inside the ball by the cone decomposition about X,
//   V(X,R) = (R³/3)·Ω_int(X) + Σ_{T∩B≠∅} [ h_T·|T∩B|/3 − (R³/3)·Ω_{T∩B} ],
// where h_T is the signed distance of T's plane from X (positive when X lies
// behind T, inside the solid) and Ω_{T∩B} the signed solid angle of T∩B seen
// from X. The plane cuts the ball in a disc; T∩disc is a signed fan about the
// disc centre of straight triangles and circular sectors (closed forms).

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace lucent {

// The ball of the query, with the powers of R the kernels use.
struct Ball {
    glm::dvec3 centre{0.0};
    double radius = 0.0;
    double radius2 = 0.0;
    double coneFactor = 0.0; // R³/3

    Ball(const glm::dvec3& x, double r)
        : centre(x), radius(r), radius2(r * r), coneFactor(r * r * r / 3.0) {}
};

// A triangle prepared for ball queries. The float box is rounded outwards, so
// it contains the exact one; one cache line holds the box and the area.
struct alignas(64) PreparedTriangle {
    glm::vec3 boxLo{0.0f};
    glm::vec3 boxHi{0.0f};
    double area = 0.0;      // 0 for a degenerate triangle, which then adds nothing
    glm::dvec3 normal{0.0}; // unit, right-handed (outward for a CCW mesh)
    glm::dvec3 p0{0.0}, p1{0.0}, p2{0.0};
};

PreparedTriangle prepareTriangle(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2);

// Signed solid angle of the triangle (a, b, c), given as vertices minus the
// eye (Van Oosterom & Strackee 1983); positive when the eye sees its back.
// 0 when the eye lies in the triangle's plane (at a vertex, edge-on) and for
// a degenerate triangle.
double triangleSolidAngle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c);

// Σ_k atan2(y_k, x_k) with one atan2 for many terms: each term with x_k > 0
// multiplies a complex product by 1 + i·y_k/x_k, whose argument is read with
// one atan2 whenever Σ|y_k/x_k| would pass 2 (so it stays within ±2 rad,
// short of any wrap). Terms with x_k ≤ 0 take their own atan2.
class HalfAngleSum {
public:
    void add(double y, double x) {
        if (!(x > 0.0)) {
            sum_ += std::atan2(y, x);
            return;
        }
        const double tan = y / x;
        if (tanSum_ + std::abs(tan) > 2.0) {
            sum_ += std::atan2(im_, re_);
            re_ = 1.0, im_ = 0.0, tanSum_ = 0.0;
        }
        const double re = re_ - im_ * tan;
        im_ += re_ * tan, re_ = re, tanSum_ += std::abs(tan);
    }
    double value() const { return sum_ + std::atan2(im_, re_); }

private:
    double sum_ = 0.0;
    double re_ = 1.0, im_ = 0.0, tanSum_ = 0.0; // the pending product
};

// |T∩B| and the signed solid angle Ω_{T∩B} seen from the ball's centre.
struct BallPart {
    double area = 0.0;
    double solidAngle = 0.0;
};

// The clip path, for a triangle that crosses the sphere, given its h (which
// callers set to exactly 0 when the ball's centre is a vertex of T). The
// solid angles of the fan's straight pieces go to `halfAngles` as halves, the
// arcs' to the result.
BallPart clippedPart(const PreparedTriangle& t, const Ball& ball, double h,
                     HalfAngleSum& halfAngles);
// The same with everything in the result.
BallPart clippedPart(const PreparedTriangle& t, const Ball& ball, double h);

enum class BallPath { Outside, Inside, Clipped };

// S and V of one ball, summed triangle by triangle:
//   S = Σ |T∩B|,  V = (R³/3)·(Ω_int − Σ Ω_{T∩B}) + Σ h_T·|T∩B|/3.
// Paths: the box reject; all three vertices inside (the whole triangle, Van
// Oosterom's tan(Ω/2) = y/x); otherwise the clip. A triangle with a vertex at
// the centre is seen edge-on: h = 0 and Ω = 0 exactly, whatever the rounding.
class BallSums {
public:
    explicit BallSums(const Ball& ball) : ball_(ball) {}

    BallPath add(const PreparedTriangle& t) {
        const glm::dvec3& x = ball_.centre;
        const double dx = std::max({double(t.boxLo.x) - x.x, x.x - double(t.boxHi.x), 0.0});
        const double dy = std::max({double(t.boxLo.y) - x.y, x.y - double(t.boxHi.y), 0.0});
        const double dz = std::max({double(t.boxLo.z) - x.z, x.z - double(t.boxHi.z), 0.0});
        if (dx * dx + dy * dy + dz * dz >= ball_.radius2 || t.area == 0.0) {
            return BallPath::Outside;
        }
        const glm::dvec3 a = t.p0 - x, b = t.p1 - x, c = t.p2 - x;
        const double a2 = glm::dot(a, a), b2 = glm::dot(b, b), c2 = glm::dot(c, c);
        const bool incident = a2 == 0.0 || b2 == 0.0 || c2 == 0.0;
        if (a2 <= ball_.radius2 && b2 <= ball_.radius2 && c2 <= ball_.radius2) {
            area_ += t.area;
            if (!incident) {
                // The triple product a·(b×c) is 2·h·|T|: Van Oosterom's numerator.
                const double triple = glm::dot(a, glm::cross(b, c));
                const double la = std::sqrt(a2), lb = std::sqrt(b2), lc = std::sqrt(c2);
                hArea_ += 0.5 * triple;
                halfAngles_.add(triple, la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb +
                                            glm::dot(b, c) * la);
            }
            return BallPath::Inside;
        }
        const double h = incident ? 0.0 : glm::dot(t.normal, a);
        if (std::abs(h) >= ball_.radius) {
            return BallPath::Outside;
        }
        const BallPart part = clippedPart(t, ball_, h, halfAngles_);
        area_ += part.area, hArea_ += h * part.area, solidAngle_ += part.solidAngle;
        return BallPath::Clipped;
    }

    double area() const { return area_; }
    double solidAngle() const { return solidAngle_ + 2.0 * halfAngles_.value(); } // Σ Ω_{T∩B}
    double volume(double interiorSolidAngle) const {
        return ball_.coneFactor * (interiorSolidAngle - solidAngle()) + hArea_ / 3.0;
    }

private:
    const Ball ball_;
    double area_ = 0.0, hArea_ = 0.0, solidAngle_ = 0.0;
    HalfAngleSum halfAngles_; // halves of the whole triangles' and straight pieces' Ω
};

// One triangle's parts of S and V for a ball: |T∩B| and
// h·|T∩B|/3 − (R³/3)·Ω_{T∩B}, its term in the sum for V.
struct BallContribution {
    double area = 0.0;
    double volume = 0.0;
    BallPath path = BallPath::Outside;
};

BallContribution ballContribution(const PreparedTriangle& t, const Ball& ball);

} // namespace lucent
