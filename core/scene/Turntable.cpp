#include "core/scene/Turntable.h"

#include <algorithm>
#include <cmath>

namespace lucent {

Camera turntableCamera(const Camera& start, double degrees, int frames, int k) {
    Camera c = start;
    c.azimuth += degrees * double(k) / double(std::max(frames, 1));
    return c;
}

Camera rotatingMipCamera(const Camera& start, int frame) {
    Camera level = start;
    level.elevation = 0.0;
    level.panRight = 0.0;
    level.panUp = 0.0;
    // Whole turns dropped first: the azimuth stays exact however long it runs.
    Camera c = turntableCamera(level, 360.0, kRotatingMipFrames, frame % kRotatingMipFrames);
    c.azimuth = std::fmod(c.azimuth, 360.0);
    if (c.azimuth < 0.0) {
        c.azimuth += 360.0;
    }
    return c;
}

} // namespace lucent
