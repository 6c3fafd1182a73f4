#pragma once
// The render options that the camera, mode and sampling messages carry, driven by
// the options table (core/scene/RenderOptions.h): a message's keys are the wire keys
// of the rows whose wireMessage names it, each value is checked with the row's kind
// and range (applyRenderOption) and travels as the table writes it. The wire adds
// its own bounds to a few keys (kWireBounds), which a server needs to keep its
// render thread responsive (a camera's reach, the finest step).

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene/RenderOptions.h"

namespace lucent::remote {

// One option's value as the table writes it ("0.25", "cubic", "true").
struct OptionValue {
    const RenderOption* option = nullptr; // a row of renderOptions()
    std::string text;
    bool operator==(const OptionValue&) const = default;
};

// What a camera, mode or sampling message carries: options in the table's order,
// each at most once; absent options keep their value.
struct OptionUpdate {
    std::vector<OptionValue> values;

    // The value of the option with this wire key; nullopt when absent.
    std::optional<std::string> text(std::string_view wireKey) const;
    // The same as a number (for Number options).
    std::optional<double> number(std::string_view wireKey) const;
    bool operator==(const OptionUpdate&) const = default;
};

// A bound the wire puts on a key on top of the table's range.
struct WireBound {
    std::string_view message;
    std::string_view key;
    double min = 0.0, max = 0.0;
    bool exclusive = false; // min and max themselves are out
    std::string_view words; // "must lie between 0.01 and 100"
};
// Camera distance and pan lie within these (mm); steps are at least this (voxels).
inline constexpr double kMaxCameraDistance = 100000.0;
inline constexpr double kMaxCameraPan = 100000.0;
inline constexpr double kMinWireStep = 0.05;
std::span<const WireBound> wireBounds();

// The rows of the table that `message` ("camera", "mode", "sampling") carries, in
// the table's order.
std::vector<const RenderOption*> wireOptions(std::string_view message);
// The row of `message` with this wire key; null when it has none.
const RenderOption* findWireOption(std::string_view message, std::string_view key);

// Checks `text` for `option` in `message` (the wire's bound, then the table's kind
// and range) and returns it as the table writes it. Throws ProtocolError
// (bad-request) that names the message and the key: "sampling: 'step' ...".
OptionValue checkedOptionValue(std::string_view message, const RenderOption& option,
                               std::string_view text);

// Every option of `message` as `description` holds it.
OptionUpdate optionUpdate(std::string_view message, const RenderDescription& description);
// Sets the update's values in `description`.
void applyOptionUpdate(const OptionUpdate& update, RenderDescription& description);

} // namespace lucent::remote
