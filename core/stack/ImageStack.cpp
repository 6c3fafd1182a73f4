#include "core/stack/ImageStack.h"

#include <algorithm>
#include <limits>

namespace lucent {

std::span<const float> ImageStack::greyFrame(int frame) const {
    return std::span<const float>(grey).subspan(pixelCount() * static_cast<std::size_t>(frame),
                                                pixelCount());
}

std::span<const std::uint8_t> ImageStack::rgbFrame(int frame) const {
    return std::span<const std::uint8_t>(rgb).subspan(
        3 * pixelCount() * static_cast<std::size_t>(frame), 3 * pixelCount());
}

std::pair<double, double> ImageStack::greyRange() const {
    if (grey.empty()) {
        return {0.0, 0.0};
    }
    const auto [lo, hi] = std::minmax_element(grey.begin(), grey.end());
    return {*lo, *hi};
}

GreyWindow ImageStack::defaultWindow() const {
    if (window.valid()) {
        return window;
    }
    const auto [lo, hi] = greyRange();
    return {(lo + hi) / 2.0, std::max(hi - lo, 1.0)};
}

std::string describeStack(int frames, const std::string& photometric, int samplesPerPixel) {
    std::string colour = photometric;
    if (samplesPerPixel == 3) {
        colour = photometric == "RGB" ? "RGB" : photometric + " colour";
    } else if (photometric == "PALETTE COLOR") {
        colour = "palette colour";
    } else {
        colour = "grey" + (photometric == "MONOCHROME1" ? std::string(", inverted") : "");
    }
    return "2D stack, " + std::to_string(frames) + (frames == 1 ? " frame, " : " frames, ") +
           colour;
}

} // namespace lucent
