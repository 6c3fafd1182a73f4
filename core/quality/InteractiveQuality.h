#pragma once
// Quality while the user drags: a coarser step and a smaller image, shown
// scaled up; the full description again once the view is still. Every
// renderer renders either; the 3D view and the render server choose (the
// server's adaptive quality varies the scale), both through this one rule.

#include "core/image/Image.h"
#include "core/scene/RenderDescription.h"

namespace lucent {

struct InteractiveQuality {
    double stepFactor = 2.0; // the step grows by this much while dragging
    double imageScale = 0.5; // and each side of the image by this factor (0, 1]
};

// The description to render while interacting: the step times stepFactor,
// each side times imageScale (at least 1 pixel). Throws std::invalid_argument
// for a factor below 1 or a scale outside (0, 1].
RenderDescription interactiveDescription(const RenderDescription& still,
                                         const InteractiveQuality& quality = {});

// Bilinear scaling of a small frame to the view's size (pixel centres aligned).
ImageRGBA8 scaledTo(const ImageRGBA8& image, int width, int height);

} // namespace lucent
