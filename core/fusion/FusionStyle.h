#pragma once
// How a fused view shows its overlay: a GL-free, Qt-free description that the MPR
// views (ui/fusion) and lucent-cli render/convert consume alike.

#include "core/fusion/FusionColourMap.h"

namespace lucent {

enum class FusionMode {
    Blend,        // the overlay's colour over the base at `opacity`
    Checkerboard, // squares of `checkerPixels` alternate base and overlay (opaque)
    Swipe         // the overlay (opaque) right of a vertical line at `swipe` of the width
};

struct FusionStyle {
    FusionColourMap colourMap = FusionColourMap::HotIron;
    double center = 0.0; // the overlay's window, in its own units (HU, SUV, ...)
    double width = 1.0;
    double opacity = 0.5; // Blend: 0 shows the base only, 1 the overlay only
    FusionMode mode = FusionMode::Blend;
    int checkerPixels = 32; // Checkerboard: the side of a square, image pixels
    double swipe = 0.5;     // Swipe: where the line is, 0 (left edge) to 1 (right edge)
    // Blend only: overlay values below the window's low end leave the base as it is
    // (PET over CT shows the CT where there is no uptake).
    bool clearBelowWindow = false;
};

const char* fusionModeName(FusionMode mode); // "blend", "checkerboard", "swipe"

} // namespace lucent
