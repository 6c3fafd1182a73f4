#include "core/stack/StackRendering.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lucent {

ImageRGBA8 renderStackFrame(const ImageStack& stack, int frame, const GreyWindow& window) {
    if (frame < 0 || frame >= stack.frameCount()) {
        throw std::out_of_range("stack frame " + std::to_string(frame) + " of " +
                                std::to_string(stack.frameCount()));
    }
    ImageRGBA8 image = ImageRGBA8::filled(stack.columns, stack.rows, 255);
    const std::size_t n = stack.pixelCount();
    if (stack.colour == StackColour::Rgb8) {
        const std::span<const std::uint8_t> rgb = stack.rgbFrame(frame);
        for (std::size_t i = 0; i < n; ++i) {
            std::copy_n(rgb.data() + 3 * i, 3, image.pixels.data() + 4 * i);
        }
        return image;
    }
    // DICOM's linear VOI function (PS3.3 C.11.2.1.2.1), to 0..255.
    const double width = std::max(window.width, 1.0);
    const double low = window.centre - 0.5 - (width - 1.0) / 2.0;
    const double scale = 255.0 / std::max(width - 1.0, 1e-9);
    const std::span<const float> grey = stack.greyFrame(frame);
    for (std::size_t i = 0; i < n; ++i) {
        const double v = std::clamp((grey[i] - low) * scale, 0.0, 255.0);
        auto g = static_cast<std::uint8_t>(std::lround(v));
        if (stack.inverted) {
            g = static_cast<std::uint8_t>(255 - g);
        }
        std::fill_n(image.pixels.data() + 4 * i, 3, g);
    }
    return image;
}

} // namespace lucent
