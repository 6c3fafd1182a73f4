#include "core/image/ColourMap.h"

#include <algorithm>
#include <cmath>

namespace lucent {
namespace {

// matplotlib's viridis at t = 0, 0.1, ..., 1 (#440154 ... #fde725).
constexpr std::array<std::array<int, 3>, 11> kStops{{{0x44, 0x01, 0x54},
                                                     {0x48, 0x24, 0x75},
                                                     {0x41, 0x44, 0x87},
                                                     {0x35, 0x5f, 0x8d},
                                                     {0x2a, 0x78, 0x8e},
                                                     {0x21, 0x91, 0x8c},
                                                     {0x22, 0xa8, 0x84},
                                                     {0x44, 0xbf, 0x70},
                                                     {0x7a, 0xd1, 0x51},
                                                     {0xbd, 0xdf, 0x26},
                                                     {0xfd, 0xe7, 0x25}}};

} // namespace

glm::dvec3 viridis(double t) {
    t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
    const double at = t * double(kStops.size() - 1);
    const std::size_t i = std::min(std::size_t(at), kStops.size() - 2);
    const double f = at - double(i);
    glm::dvec3 c;
    for (int k = 0; k < 3; ++k) {
        c[k] = ((1.0 - f) * kStops[i][std::size_t(k)] + f * kStops[i + 1][std::size_t(k)]) / 255.0;
    }
    return c;
}

std::array<std::uint8_t, 3> viridisBytes(double value, double lo, double hi) {
    const glm::dvec3 c = viridis(hi > lo ? (value - lo) / (hi - lo) : 0.5);
    return {std::uint8_t(c.r * 255.0 + 0.5), std::uint8_t(c.g * 255.0 + 0.5),
            std::uint8_t(c.b * 255.0 + 0.5)};
}

} // namespace lucent
