#pragma once
// The overlay of a fused render (RenderOverlay in core/scene/RenderDescription.h) as the
// CPU ray kernels sample it; its table and fingerprint serve the GPU's too
// (render/OverlayTextures).
//
// Mixing rule, one lattice sample (both ray casters):
//  - the overlay's value v (trilinear; NaN outside the overlay: no contribution) picks entry
//    i = windowToGrey(v, center, width) of a 256-entry table: colour = the map's entry i,
//    opacity a_o = opacity * i / 255 per voxel of the smallest spacing, corrected for the
//    step as the transfer function's (a' = 1 - (1 - a)^(dt / dt_ref));
//  - DVR: with the base's classified (and shaded) sample (c_b, a_b), the fused sample is
//    a = a_b + a_o - a_b a_o (the two opacities combined as independent absorbers) and
//    c = (a_b c_b + a_o c_o) / (a_b + a_o) (colours weighted by opacity), composited front
//    to back as any sample. a_o = 0 leaves the base's sample as it is, bit for bit;
//  - MIP, MinIP, average: the base's projection P (premultiplied) with the overlay's own
//    maximum m along the ray over it: P (1 - a) + (c_o(m) a, a) with a = opacity * i(m) / 255
//    (no step correction: a projection is one value).
// The overlay's colour is not shaded: uptake has no surfaces.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>

#include <glm/glm.hpp>

#include "core/fusion/FusionColourMap.h"
#include "core/fusion/FusionStyle.h"
#include "core/raycast/VolumeFields.h"
#include "core/volume/Volume.h"

namespace lucent {

// One entry of the overlay's table: colour (0..1), opacity corrected for the step, raw.
struct OverlayEntry {
    glm::vec3 colour{0.0f};
    float alpha = 0.0f;
    float rawAlpha = 0.0f;
};
using OverlayTable = std::array<OverlayEntry, 256>;

// The overlay's table for a step of stepRatio voxels: the map's colours, opacity * i / 255
// raw and corrected for the step. Both ray casters use it (the GPU's as a texture).
inline OverlayTable overlayTable(const FusionStyle& style, double stepRatio) {
    OverlayTable t;
    const ColourLut& lut = colourLut(style.colourMap);
    for (std::size_t i = 0; i < t.size(); ++i) {
        const double a = std::clamp(style.opacity, 0.0, 1.0) * double(i) / 255.0;
        t[i].colour = glm::vec3(lut[i][0], lut[i][1], lut[i][2]) / 255.0f;
        t[i].rawAlpha = float(a);
        t[i].alpha = a <= 0.0 ? 0.0f : float(1.0 - std::pow(1.0 - std::min(a, 1.0), stepRatio));
    }
    return t;
}

// What tells one overlay volume from another for the casters' caches: its address, its
// voxels' address, its grid and a hash of 4096 of its values spread over it. (A view
// that resamples its overlay anew usually gets a new Volume; one that reuses an address
// with other values is told apart by the hash.)
inline std::uint64_t overlayFingerprint(const Volume& overlay) {
    std::uint64_t h = 1469598103934665603ull; // FNV-1a
    const auto mix = [&h](std::uint64_t v) {
        for (int b = 0; b < 8; ++b) {
            h = (h ^ ((v >> (8 * b)) & 0xffu)) * 1099511628211ull;
        }
    };
    mix(reinterpret_cast<std::uintptr_t>(&overlay));
    mix(reinterpret_cast<std::uintptr_t>(overlay.bytes().data()));
    const glm::ivec3 d = overlay.dims();
    mix(std::uint64_t(d.x) | std::uint64_t(d.y) << 21 | std::uint64_t(d.z) << 42);
    const std::span<const std::byte> bytes = overlay.bytes();
    const std::size_t step = std::max<std::size_t>(8, bytes.size() / 4096 / 8 * 8);
    for (std::size_t at = 0; at + 8 <= bytes.size(); at += step) {
        std::uint64_t v = 0;
        std::memcpy(&v, bytes.data() + at, 8);
        mix(v);
    }
    return h;
}

// What a kernel without an overlay carries: nothing.
struct NoOverlay {
    static constexpr bool kEnabled = false;
};

template <class Real> struct OverlaySampler {
    static constexpr bool kEnabled = true;
    LinearField<Real, float> field;
    const OverlayTable* table = nullptr;
    double low = 0.0;   // the window's low end
    double width = 1.0; // above 0

    Real value(const Vec3<Real>& p) const { return field.value(p); }
    // The entry of v, null for NaN (no overlay there).
    const OverlayEntry* entry(Real v) const {
        if (std::isnan(v)) {
            return nullptr;
        }
        // windowToGrey (core/mpr/PlaneSampler.cpp): the same rounding.
        const long i = std::lround((double(v) - low) / width * 255.0);
        return &(*table)[std::size_t(std::clamp(i, 0L, 255L))];
    }
};

} // namespace lucent
