#include "core/fusion/FusionCompositor.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/mpr/PlaneSampler.h"

namespace lucent {
namespace {

std::uint8_t mix(Rgb32 base, int shift, std::uint8_t colour, double alpha) {
    const double b = static_cast<double>((base >> shift) & 0xffu);
    return static_cast<std::uint8_t>(std::lround(b + (colour - b) * alpha));
}

} // namespace

const char* fusionModeName(FusionMode mode) {
    switch (mode) {
    case FusionMode::Blend:
        return "blend";
    case FusionMode::Checkerboard:
        return "checkerboard";
    case FusionMode::Swipe:
        return "swipe";
    }
    return "blend";
}

bool showsOverlay(const FusionStyle& style, int x, int y, int width) {
    switch (style.mode) {
    case FusionMode::Blend:
        return true;
    case FusionMode::Checkerboard: {
        const int side = std::max(1, style.checkerPixels);
        return ((x / side) + (y / side)) % 2 == 1;
    }
    case FusionMode::Swipe:
        return x >= style.swipe * width;
    }
    return true;
}

std::vector<Rgb32> composeFusion(std::span<const Rgb32> base, std::span<const float> overlay,
                                 int width, int height, const FusionStyle& style) {
    const std::size_t count = static_cast<std::size_t>(std::max(0, width)) *
                              static_cast<std::size_t>(std::max(0, height));
    if (base.size() != count || overlay.size() != count) {
        throw std::invalid_argument("composeFusion: the base and overlay images differ in size");
    }
    std::vector<Rgb32> out(base.begin(), base.end());
    const ColourLut& lut = colourLut(style.colourMap);
    const double alpha =
        style.mode == FusionMode::Blend ? std::clamp(style.opacity, 0.0, 1.0) : 1.0;
    const double low = style.center - 0.5 * style.width;
    const bool clear = style.mode == FusionMode::Blend && style.clearBelowWindow;
#pragma omp parallel for schedule(static)
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * width + x;
            const float value = overlay[i];
            if (std::isnan(value) || !showsOverlay(style, x, y, width) || (clear && value < low)) {
                continue;
            }
            const auto& c = lut[windowToGrey(value, style.center, style.width)];
            out[i] = rgb32(mix(base[i], 16, c[0], alpha), mix(base[i], 8, c[1], alpha),
                           mix(base[i], 0, c[2], alpha));
        }
    }
    return out;
}

std::vector<Rgb32> greyToRgb32(std::span<const std::uint8_t> grey) {
    std::vector<Rgb32> out(grey.size());
    std::transform(grey.begin(), grey.end(), out.begin(), greyRgb32);
    return out;
}

} // namespace lucent
