#pragma once
// Version 4: MPR slices in a client (docs/protocol.md, "Slices"). The client's
// `slices` message says which slices it shows, through which crosshair point and
// with which window; the server renders each through core/mpr (as the
// workstation's SliceView does) and sends it as a grey PNG frame whose header
// carries the plane, so that the client can turn a click into patient
// millimetres and draw the crosshair.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "core/mpr/PlaneSampler.h"

namespace lucent::remote {

// Slices are at least kMinImageSide and at most this wide and tall.
inline constexpr int kMaxSliceSide = 2048;
// The crosshair's coordinates and a window's centre and width lie within this (mm, data units).
inline constexpr double kMaxSliceCoordinate = 100000.0;

// "axial", "coronal", "sagittal"; the inverse gives nullopt for another name.
std::string_view sliceViewName(Orientation view);
std::optional<Orientation> sliceViewNamed(std::string_view name);

struct SliceWindow {
    double center = 40.0;
    double width = 400.0;
    bool operator==(const SliceWindow&) const = default;
};

// {"type":"slices",...}: every field optional, an absent one keeps its value.
// `window` is either numbers or the name of a window preset (core/mpr/WindowPresets:
// "Brain", ... "Bone"), never both; an empty `views` stops the slices.
struct SlicesRequest {
    std::optional<glm::dvec3> crosshair; // LPS mm
    std::optional<SliceWindow> window;
    std::optional<std::string> windowPreset;
    std::optional<glm::ivec2> size; // of each slice, pixels
    std::optional<std::vector<Orientation>> views;
    bool operator==(const SlicesRequest&) const = default;
};

// What a slice frame's header adds to a frame's: which view, the crosshair and
// window it shows, and its plane: pixel (x, y) (centres at whole numbers) lies at
// centre + u * (x - (width - 1) / 2) * pixelMm + v * (y - (height - 1) / 2) * pixelMm;
// the wheel moves the crosshair by stepMm along u x v (one voxel).
struct SliceFrameInfo {
    Orientation view = Orientation::Axial;
    glm::dvec3 crosshair{0.0};
    SliceWindow window;
    glm::dvec3 centre{0.0};
    glm::dvec3 u{1.0, 0.0, 0.0};
    glm::dvec3 v{0.0, 1.0, 0.0};
    double pixelMm = 1.0;
    double stepMm = 1.0;
    bool operator==(const SliceFrameInfo&) const = default;
};

// A window preset as hello (version 4) lists them for a client's picker.
struct WindowPresetInfo {
    std::string name;
    double center = 0.0;
    double width = 0.0;
    bool operator==(const WindowPresetInfo&) const = default;
};
// core/mpr's presets, in their order (keys 1 to 8).
std::vector<WindowPresetInfo> windowPresetInfos();

} // namespace lucent::remote
