#pragma once
// One description of a render, shared by the CPU reference ray caster and the
// GPU ray caster, so that their images can be compared pixel by pixel.
//
// Sampling convention (both renderers): a ray starts where it enters the
// volume's box (voxel centres 0 .. dims-1, intersected with the clip box);
// samples lie at t_entry + n * dt, dt = step * (smallest spacing), whatever
// bricks they fall in; colour is premultiplied and composited front to back;
// opacity is corrected a' = 1 - (1 - a)^(dt / dt_ref), dt_ref = one voxel of
// the smallest spacing.

#include <glm/glm.hpp>

#include "core/fusion/FusionStyle.h"
#include "core/scene/Camera.h"
#include "core/tf/TransferFunction.h"
#include "core/volume/BrickGrid.h"
#include "core/volume/Volume.h"

namespace lucent {

enum class RenderMode { Dvr, Mip, MinIp, Average, Isosurface };
enum class Interpolation { Nearest, Linear, Cubic };
enum class Classification { Post, Pre };
enum class Precision { Double, Float };

const char* renderModeName(RenderMode mode);
const char* interpolationName(Interpolation interp);

struct SamplingSettings {
    double step = 0.5; // in voxels of the smallest spacing
    Interpolation interpolation = Interpolation::Linear;
    Classification classification = Classification::Post;
    bool preintegrate = false;
    double earlyTermination = 0.99; // stop when accumulated opacity reaches this
    int brickSize = 64;
    bool emptySpaceLeaping = true;
    // GL caster, with leaping: a leap crosses every leapt cell within the
    // distance map's reach at once (render/LeapTextures.h), not one cell.
    bool leapDistance = true;
    // GL caster, DVR with post-classification, trilinear or nearest: samples
    // in blocks of 2^3 voxels that show nothing are passed over, several
    // blocks at once, without reading the volume.
    bool blockSkipping = true;
    Precision precision = Precision::Float;
    // The CPU ray caster marches eight rays at once with SIMD (AVX2) where the
    // CPU has it; false forces its scalar kernels (tests compare the two). The
    // image is the same either way.
    bool simd = true;
};

// A second volume drawn along the same rays (3D fusion, DESIGN.md "Fusion"): already on the
// grid of the description's volume (resampleOverlay in core/fusion/OverlayResampler.h makes
// it), Float32, NaN where it has no value. It is sampled trilinearly at the base's lattice
// samples; a sample's entry i = windowToGrey(value, center, width) of the style's window gives
// its colour (the map's entry i) and its opacity (opacity * i / 255 per voxel of the smallest
// spacing, corrected for the step as the transfer function's is). DVR mixes it with the base's
// classified sample; MIP, MinIP and average draw the overlay's own maximum over the base's
// projection. Of the style only the colour map, the window and the opacity apply (the mode,
// checkerboard and swipe are the MPR views'). Not with isosurfaces.
struct RenderOverlay {
    const Volume* volume = nullptr; // null: no overlay
    // Hot iron at opacity 0.5; width 0: the window is not chosen yet ("auto": the
    // overlay's defaultWindow, set by resolveOverlayWindow).
    FusionStyle style = [] {
        FusionStyle s;
        s.width = 0.0;
        return s;
    }();
};

struct RenderDescription {
    const Volume* volume = nullptr;
    TransferFunction transferFunction; // its shading.enabled switches shading
    Camera camera;
    RenderMode mode = RenderMode::Dvr;
    double isoValue = 300.0; // for RenderMode::Isosurface, in data units (HU for CT)
    ClipBox clip;            // in voxel index coordinates
    SamplingSettings sampling;
    int width = 512;
    int height = 512;
    glm::dvec3 background{0.0};
    RenderOverlay overlay;

    // Throws std::invalid_argument naming the setting that is out of range.
    void validate() const;
};

// Sets an overlay window that is still "auto" (width <= 0) to the overlay volume's
// defaultWindow (core/mpr/PlaneSampler.h: L 40 W 400 for CT, else its 1st to 99th
// percentile). Does nothing without an overlay.
void resolveOverlayWindow(RenderOverlay& overlay);

} // namespace lucent
