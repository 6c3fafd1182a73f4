#include "core/quality/InteractiveQuality.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lucent {

RenderDescription interactiveDescription(const RenderDescription& still,
                                         const InteractiveQuality& quality) {
    if (!(quality.stepFactor >= 1.0) || !(quality.imageScale > 0.0 && quality.imageScale <= 1.0)) {
        throw std::invalid_argument("interactive quality: the step factor must be at least 1 and "
                                    "the image scale lie in (0, 1]");
    }
    RenderDescription d = still;
    d.sampling.step *= quality.stepFactor;
    d.width = std::max(1, int(still.width * quality.imageScale));
    d.height = std::max(1, int(still.height * quality.imageScale));
    return d;
}

ImageRGBA8 scaledTo(const ImageRGBA8& image, int width, int height) {
    ImageRGBA8 out = ImageRGBA8::filled(width, height, 255);
    if (image.width < 1 || image.height < 1) {
        return out;
    }
    const double sx = double(image.width) / width, sy = double(image.height) / height;
    for (int y = 0; y < height; ++y) {
        const double fy = std::clamp((y + 0.5) * sy - 0.5, 0.0, double(image.height - 1));
        const int y0 = int(fy), y1 = std::min(y0 + 1, image.height - 1);
        const double wy = fy - y0;
        for (int x = 0; x < width; ++x) {
            const double fx = std::clamp((x + 0.5) * sx - 0.5, 0.0, double(image.width - 1));
            const int x0 = int(fx), x1 = std::min(x0 + 1, image.width - 1);
            const double wx = fx - x0;
            for (int c = 0; c < 4; ++c) {
                const double top = image.at(x0, y0)[c] * (1 - wx) + image.at(x1, y0)[c] * wx;
                const double bottom = image.at(x0, y1)[c] * (1 - wx) + image.at(x1, y1)[c] * wx;
                out.at(x, y)[c] = std::uint8_t(std::lround(top * (1 - wy) + bottom * wy));
            }
        }
    }
    return out;
}

} // namespace lucent
