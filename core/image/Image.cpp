#include "core/image/Image.h"

#include <stdexcept>
#include <string>

namespace lucent {

ImageRGBA8 ImageRGBA8::filled(int width, int height, std::uint8_t fill) {
    if (width < 0 || height < 0) {
        throw std::invalid_argument("image size must not be negative: " + std::to_string(width) +
                                    "x" + std::to_string(height));
    }
    ImageRGBA8 image{width, height, {}};
    image.pixels.assign(4 * image.pixelCount(), fill);
    return image;
}

} // namespace lucent
