#include "core/mpr/WindowPresets.h"

#include <array>

namespace lucent {

namespace {

constexpr std::array<WindowPreset, 8> kPresets{{
    {"Brain", 40.0, 80.0},
    {"Subdural", 75.0, 215.0},
    {"Stroke", 32.0, 8.0},
    {"Lung", -600.0, 1500.0},
    {"Mediastinum", 50.0, 350.0},
    {"Abdomen", 50.0, 400.0},
    {"Liver", 30.0, 150.0},
    {"Bone", 400.0, 1800.0},
}};

} // namespace

std::span<const WindowPreset> windowPresets() {
    return kPresets;
}

const WindowPreset* findWindowPreset(std::string_view name) {
    for (const WindowPreset& preset : kPresets) {
        if (preset.name == name) {
            return &preset;
        }
    }
    return nullptr;
}

} // namespace lucent
