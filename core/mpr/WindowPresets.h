#pragma once

#include <span>
#include <string_view>

namespace lucent {

// A named CT window (Hounsfield units), as radiologists know them.
struct WindowPreset {
    std::string_view name;
    double center;
    double width;
};

// Brain, subdural, stroke, lung, mediastinum, abdomen, liver, bone, in that order
// (the SliceView's keys 1 to 8 pick them).
std::span<const WindowPreset> windowPresets();

// The preset of that name (case-sensitive, as listed), or nullptr.
const WindowPreset* findWindowPreset(std::string_view name);

} // namespace lucent
