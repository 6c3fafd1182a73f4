#include "core/raycast/PartProjection.h"

#include <algorithm>

namespace lucent {

float projectionDepth(RenderMode mode, glm::vec2 projection, double lo, double hi) {
    if (projection.y <= 0.0f) {
        return 1.0f;
    }
    const double span = hi > lo ? hi - lo : 1.0;
    const double t = std::clamp((double(projection.x) - lo) / span, 0.0, 1.0);
    // Kept below 1 so that a sample never reads as "nothing here".
    constexpr double kBelowOne = 1.0 - 1.0 / 16777216.0;
    return float((mode == RenderMode::MinIp ? t : 1.0 - t) * kBelowOne);
}

glm::vec4 averageColour(const TransferFunction& tf, glm::vec2 sumAndCount) {
    if (sumAndCount.y <= 0.0f) {
        return glm::vec4(0.0f);
    }
    const double v = double(sumAndCount.x) / double(sumAndCount.y);
    const double a = tf.opacityAt(v);
    return glm::vec4(glm::vec3(tf.colourAt(v) * a), float(a));
}

} // namespace lucent
