#pragma once
// Quality while the user drags: a coarser step and a smaller image, shown
// scaled up; the full description again once the view is still. Both ray
// casters render either; the 3D view chooses.

#include "core/image/Image.h"
#include "core/scene/RenderDescription.h"

namespace lucent {

struct InteractiveQuality {
    double stepFactor = 2.0; // the step grows by this much while dragging
    int imageDivisor = 2;    // and the image shrinks by this much on each side
};

// The description to render while interacting. Throws std::invalid_argument
// for a factor below 1 or a divisor below 1.
RenderDescription interactiveDescription(const RenderDescription& still,
                                         const InteractiveQuality& quality = {});

// Bilinear scaling of a small frame to the view's size (pixel centres aligned).
ImageRGBA8 scaledTo(const ImageRGBA8& image, int width, int height);

} // namespace lucent
