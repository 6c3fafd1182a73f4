#include "core/scene/ImageProjection.h"

namespace lucent {

ImageProjection imageProjection(const ViewFrame& f) {
    // ViewFrame::screenX and screenY solved for the fraction: u = (sx / (t a) + 1) / 2 and
    // v = (1 - sy / t) / 2, with sx, sy the point's right and up over its depth.
    const double ta = f.tanHalfFov * f.aspect, t = f.tanHalfFov;
    const glm::dvec3 rows[3] = {0.5 * (f.right / ta + f.forward), 0.5 * (f.forward - f.up / t),
                                f.forward};
    ImageProjection m{};
    for (int r = 0; r < 3; ++r) {
        m[std::size_t(4 * r)] = rows[r].x;
        m[std::size_t(4 * r + 1)] = rows[r].y;
        m[std::size_t(4 * r + 2)] = rows[r].z;
        m[std::size_t(4 * r + 3)] = -glm::dot(rows[r], f.eye);
    }
    return m;
}

std::optional<glm::dvec2> projectToImage(const ImageProjection& m, const glm::dvec3& p) {
    double out[3];
    for (std::size_t r = 0; r < 3; ++r) {
        out[r] = m[4 * r] * p.x + m[4 * r + 1] * p.y + m[4 * r + 2] * p.z + m[4 * r + 3];
    }
    if (!(out[2] > 1e-9)) {
        return std::nullopt;
    }
    return glm::dvec2(out[0] / out[2], out[1] / out[2]);
}

glm::dvec3 rayThroughFraction(const ViewFrame& frame, glm::dvec2 fraction, int width, int height) {
    return frame.rayDirection(fraction.x * width - 0.5, fraction.y * height - 0.5, width, height);
}

} // namespace lucent
