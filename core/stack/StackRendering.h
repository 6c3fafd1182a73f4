#pragma once
// A frame of an ImageStack as an 8-bit RGBA image: grey through a window (MONOCHROME1
// inverted), colour as it is.

#include "core/image/Image.h"
#include "core/stack/ImageStack.h"

namespace lucent {

// Throws std::out_of_range for a frame outside the stack.
ImageRGBA8 renderStackFrame(const ImageStack& stack, int frame, const GreyWindow& window);

} // namespace lucent
