#pragma once
// The render options, described once: name, kind, range, default, command-line
// flag, wire key and help. This table drives RenderDescription::validate(), the
// CLI's parser (lucent-cli render, bench), the protocol's sampling and camera
// codec, and the option list in docs/options.md (`lucent-cli options
// --markdown` prints it; a test keeps the two equal), as f3d's options.json
// drives its CLI, API and documentation.

#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/scene/RenderDescription.h"

namespace lucent {

enum class OptionKind {
    Number,  // a finite double within [min, max]
    Integer, // a whole number within [min, max]
    Choice,  // one of `choices`
    Switch,  // true or false
    Size,    // WIDTHxHEIGHT
    Box,     // "X0,Y0,Z0,X1,Y1,Z1" (voxel indices, corners included) or "all"
    Window,  // "C,W" (a centre and a width above 0) or "auto"
};

// Which protocol message carries an option ("" : not on the wire).
inline constexpr std::string_view kWireCamera = "camera";
inline constexpr std::string_view kWireSampling = "sampling";
inline constexpr std::string_view kWireMode = "mode";

struct RenderOption {
    std::string_view name;  // the option's one name, as in the docs
    std::string_view words; // how error messages call it ("image size")
    OptionKind kind = OptionKind::Number;
    double min = 0.0, max = 0.0; // Number, Integer: inclusive
    std::vector<std::string_view> choices;
    std::string_view cliFlag;   // without dashes; "" : not on the command line
    std::string_view cliSets;   // a flag that takes no value sets this one ("" : takes a value)
    std::string_view valueName; // the CLI's placeholder, "VOXELS"
    std::string_view wireMessage;
    std::string_view wireKey;
    std::string_view help;
    // The option's value in a description, as text ("0.5", "cubic", "true").
    std::string (*read)(const RenderDescription&) = nullptr;
    // Sets it from text already checked against kind, range and choices.
    void (*write)(RenderDescription&, std::string_view) = nullptr;
};

// Every option, in the order the docs and --help list them.
std::span<const RenderOption> renderOptions();
// The option of this name (or CLI flag), or null.
const RenderOption* findRenderOption(std::string_view name);

// Parses `text` for `option` and sets it in `description`. Throws
// std::invalid_argument naming the option, the text and what it must be.
void applyRenderOption(RenderDescription& description, const RenderOption& option,
                       std::string_view text);
// The option's value in `description` as text.
std::string renderOptionValue(const RenderDescription& description, const RenderOption& option);
// The default description's value, as text (what --help and the docs print).
std::string renderOptionDefault(const RenderOption& option);
// Throws std::invalid_argument naming the first option whose value in
// `description` lies outside the table's range.
void checkRenderOptionRanges(const RenderDescription& description);

// "WIDTHxHEIGHT", each side 1..kMaxImageSide. Throws std::invalid_argument.
inline constexpr int kMaxImageSide = 16384;
std::pair<int, int> parseImageSize(std::string_view text);

// A clip box as text: "X0,Y0,Z0,X1,Y1,Z1" in voxel indices, each corner's
// coordinate at most the other's, or "all" (no clip). Throws std::invalid_argument.
ClipBox parseClipBox(std::string_view text);
std::string clipBoxText(const ClipBox& box);

// A window as text: "C,W", the centre and a width above 0, both finite; "auto" gives
// width 0 (resolved later, see resolveOverlayWindow). Throws std::invalid_argument.
std::pair<double, double> parseWindow(std::string_view text);
std::string windowText(double center, double width); // "auto" for a width <= 0

// The option list as a Markdown table (docs/options.md).
std::string renderOptionsMarkdown();

} // namespace lucent
