#pragma once
// Whether two descriptions cast the same frame (all but the background): what
// GpuRayCaster::drawInPlace asks before it casts again. The structured bindings name
// every field, so that a field added to one of these structs fails to compile here
// until it is compared. Private to render/.

#include <tuple>

#include "core/scene/RenderDescription.h"

namespace lucent::castkey {

inline auto fields(const Camera& c) {
    const auto& [azimuth, elevation, zoom, fieldOfView, distance, panRight, panUp] = c;
    return std::tie(azimuth, elevation, zoom, fieldOfView, distance, panRight, panUp);
}
inline auto fields(const ClipBox& c) {
    const auto& [lo, hi] = c;
    return std::tie(lo, hi);
}
inline auto fields(const SamplingSettings& s) {
    const auto& [step, interpolation, classification, preintegrate, earlyTermination, brickSize,
                 emptySpaceLeaping, leapDistance, blockSkipping, precision, simd] = s;
    return std::tie(step, interpolation, classification, preintegrate, earlyTermination, brickSize,
                    emptySpaceLeaping, leapDistance, blockSkipping, precision, simd);
}
// What of an overlay the cast draws: the volume, the map, the window and the opacity
// (the style's MPR fields, mode, checkerboard and swipe, do not).
inline auto fields(const RenderOverlay& o) {
    const auto& [volume, style] = o;
    return std::tie(volume, style.colourMap, style.center, style.width, style.opacity);
}

// Whether a and b (of a caster's own volume: null or that one) cast the same frame.
inline bool sameCast(const RenderDescription& a, const RenderDescription& b) {
    const auto& [volume, transferFunction, camera, mode, isoValue, clip, sampling, width, height,
                 background, overlay] = a;
    (void)volume;     // both are the caster's
    (void)background; // composited after the cast
    return transferFunction == b.transferFunction && fields(camera) == fields(b.camera) &&
           mode == b.mode && isoValue == b.isoValue && fields(clip) == fields(b.clip) &&
           fields(sampling) == fields(b.sampling) && width == b.width && height == b.height &&
           fields(overlay) == fields(b.overlay);
}

} // namespace lucent::castkey
