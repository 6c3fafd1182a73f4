#include "core/scene/RenderOptions.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

// Each row names only the fields it sets (designated initializers); the rest
// keep their defaults, which GCC's -Wextra would report one by one.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace lucent {
namespace {

constexpr double kHuge = 1e300;
constexpr double kTiny = std::numeric_limits<double>::min(); // a range "above 0"

// The shortest text that reads back as v.
std::string number(double v) {
    char text[32];
    const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
    return ec == std::errc() ? std::string(text, end) : std::string("?");
}

double parseNumber(std::string_view text) {
    double v = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty()) {
        throw std::invalid_argument("not a number");
    }
    return v;
}

std::string choiceText(std::span<const std::string_view> choices) {
    std::string known;
    for (const std::string_view c : choices) {
        known += (known.empty() ? "" : ", ") + std::string(c);
    }
    return known;
}

template <class E>
E fromName(std::string_view text, std::initializer_list<std::pair<std::string_view, E>> names) {
    for (const auto& [name, value] : names) {
        if (name == text) {
            return value;
        }
    }
    throw std::logic_error("render option: unchecked choice");
}

bool isTrue(std::string_view text) {
    return text == "true";
}
std::string boolText(bool b) {
    return b ? "true" : "false";
}

const char* classificationName(Classification c) {
    return c == Classification::Pre ? "pre" : "post";
}
const char* precisionName(Precision p) {
    return p == Precision::Double ? "double" : "float";
}

// One row per option; `read` and `write` reach its field.
std::vector<RenderOption> makeTable() {
    using D = RenderDescription;
    using sv = std::string_view;
    std::vector<RenderOption> t;
    t.push_back(
        {.name = "size",
         .words = "image size",
         .kind = OptionKind::Size,
         .min = 1,
         .max = kMaxImageSide,
         .cliFlag = "size",
         .valueName = "WxH",
         .help = "Image size in pixels.",
         .read =
             [](const D& d) { return std::to_string(d.width) + "x" + std::to_string(d.height); },
         .write = [](D& d, sv v) { std::tie(d.width, d.height) = parseImageSize(v); }});
    t.push_back({.name = "clip",
                 .words = "clip box",
                 .kind = OptionKind::Box,
                 .cliFlag = "clip",
                 .valueName = "X0,Y0,Z0,X1,Y1,Z1",
                 .help = "Clip box in voxel indices (both corners included); all: none.",
                 .read = [](const D& d) { return clipBoxText(d.clip); },
                 .write = [](D& d, sv v) { d.clip = parseClipBox(v); }});
    t.push_back({.name = "mode",
                 .words = "mode",
                 .kind = OptionKind::Choice,
                 .choices = {"dvr", "mip", "minip", "avg", "iso"},
                 .cliFlag = "mode",
                 .valueName = "MODE",
                 .wireMessage = kWireMode,
                 .wireKey = "mode",
                 .help = "Direct volume rendering, maximum or minimum intensity projection, "
                         "average, or isosurface.",
                 .read = [](const D& d) { return std::string(renderModeName(d.mode)); },
                 .write =
                     [](D& d, sv v) {
                         d.mode = fromName<RenderMode>(v, {{"dvr", RenderMode::Dvr},
                                                           {"mip", RenderMode::Mip},
                                                           {"minip", RenderMode::MinIp},
                                                           {"avg", RenderMode::Average},
                                                           {"iso", RenderMode::Isosurface}});
                     }});
    t.push_back({.name = "iso",
                 .words = "iso value",
                 .kind = OptionKind::Number,
                 .min = -kHuge,
                 .max = kHuge,
                 .cliFlag = "iso",
                 .valueName = "VALUE",
                 .wireMessage = kWireMode,
                 .wireKey = "iso",
                 .help = "Isosurface value in data units (HU for CT).",
                 .read = [](const D& d) { return number(d.isoValue); },
                 .write = [](D& d, sv v) { d.isoValue = parseNumber(v); }});
    auto angle = [](sv name, sv help) {
        return RenderOption{.name = name,
                            .words = name,
                            .kind = OptionKind::Number,
                            .min = -kHuge,
                            .max = kHuge,
                            .cliFlag = name,
                            .valueName = "DEG",
                            .wireMessage = kWireCamera,
                            .wireKey = name,
                            .help = help};
    };
    RenderOption azimuth = angle("azimuth", "Turn about the head-foot axis, degrees.");
    azimuth.read = [](const D& d) { return number(d.camera.azimuth); };
    azimuth.write = [](D& d, sv v) { d.camera.azimuth = parseNumber(v); };
    t.push_back(azimuth);
    RenderOption elevation = angle("elevation", "Turn about the left-right axis, degrees.");
    elevation.read = [](const D& d) { return number(d.camera.elevation); };
    elevation.write = [](D& d, sv v) { d.camera.elevation = parseNumber(v); };
    t.push_back(elevation);
    t.push_back({.name = "zoom",
                 .words = "zoom",
                 .kind = OptionKind::Number,
                 .min = kTiny,
                 .max = kHuge,
                 .cliFlag = "zoom",
                 .valueName = "F",
                 .wireMessage = kWireCamera,
                 .wireKey = "zoom",
                 .help = "Magnification; 1 fits the volume.",
                 .read = [](const D& d) { return number(d.camera.zoom); },
                 .write = [](D& d, sv v) { d.camera.zoom = parseNumber(v); }});
    t.push_back({.name = "distance",
                 .words = "camera distance",
                 .kind = OptionKind::Number,
                 .min = 0.0,
                 .max = kHuge,
                 .cliFlag = "distance",
                 .valueName = "MM",
                 .wireMessage = kWireCamera,
                 .wireKey = "distance",
                 .help = "Eye to the point looked at, mm; 0 fits the volume, less than the "
                         "volume's radius puts the eye inside.",
                 .read = [](const D& d) { return number(d.camera.distance); },
                 .write = [](D& d, sv v) { d.camera.distance = parseNumber(v); }});
    t.push_back({.name = "pan-right",
                 .words = "camera pan",
                 .kind = OptionKind::Number,
                 .min = -kHuge,
                 .max = kHuge,
                 .cliFlag = "pan-right",
                 .valueName = "MM",
                 .wireMessage = kWireCamera,
                 .wireKey = "pan_right",
                 .help = "Move the point looked at to the view's right, mm.",
                 .read = [](const D& d) { return number(d.camera.panRight); },
                 .write = [](D& d, sv v) { d.camera.panRight = parseNumber(v); }});
    t.push_back({.name = "pan-up",
                 .words = "camera pan",
                 .kind = OptionKind::Number,
                 .min = -kHuge,
                 .max = kHuge,
                 .cliFlag = "pan-up",
                 .valueName = "MM",
                 .wireMessage = kWireCamera,
                 .wireKey = "pan_up",
                 .help = "Move the point looked at up in the view, mm.",
                 .read = [](const D& d) { return number(d.camera.panUp); },
                 .write = [](D& d, sv v) { d.camera.panUp = parseNumber(v); }});
    t.push_back({.name = "step",
                 .words = "step",
                 .kind = OptionKind::Number,
                 .min = 1e-4,
                 .max = kHuge,
                 .cliFlag = "step",
                 .valueName = "VOXELS",
                 .wireMessage = kWireSampling,
                 .wireKey = "step",
                 .help = "Sampling step in voxels of the smallest spacing.",
                 .read = [](const D& d) { return number(d.sampling.step); },
                 .write = [](D& d, sv v) { d.sampling.step = parseNumber(v); }});
    t.push_back(
        {.name = "interp",
         .words = "interpolation",
         .kind = OptionKind::Choice,
         .choices = {"nearest", "linear", "cubic"},
         .cliFlag = "interp",
         .valueName = "NAME",
         .wireMessage = kWireSampling,
         .wireKey = "interp",
         .help = "Reconstruction filter: nearest, trilinear, or tricubic B-spline on "
                 "prefiltered coefficients.",
         .read =
             [](const D& d) { return std::string(interpolationName(d.sampling.interpolation)); },
         .write =
             [](D& d, sv v) {
                 d.sampling.interpolation =
                     fromName<Interpolation>(v, {{"nearest", Interpolation::Nearest},
                                                 {"linear", Interpolation::Linear},
                                                 {"cubic", Interpolation::Cubic}});
             }});
    t.push_back(
        {.name = "classification",
         .words = "classification",
         .kind = OptionKind::Choice,
         .choices = {"post", "pre"},
         .cliFlag = "preclassify",
         .cliSets = "pre",
         .wireMessage = kWireSampling,
         .wireKey = "classification",
         .help = "Classify after interpolation (post) or the voxels before it (pre).",
         .read =
             [](const D& d) { return std::string(classificationName(d.sampling.classification)); },
         .write =
             [](D& d, sv v) {
                 d.sampling.classification =
                     v == "pre" ? Classification::Pre : Classification::Post;
             }});
    t.push_back({.name = "preintegrate",
                 .words = "pre-integration",
                 .kind = OptionKind::Switch,
                 .cliFlag = "preintegrate",
                 .cliSets = "true",
                 .wireMessage = kWireSampling,
                 .wireKey = "preintegrate",
                 .help = "Pre-integrated transfer function (slab integration between samples).",
                 .read = [](const D& d) { return boolText(d.sampling.preintegrate); },
                 .write = [](D& d, sv v) { d.sampling.preintegrate = isTrue(v); }});
    t.push_back({.name = "shading",
                 .words = "shading",
                 .kind = OptionKind::Switch,
                 .cliFlag = "no-shading",
                 .cliSets = "false",
                 .wireMessage = kWireSampling,
                 .wireKey = "shading",
                 .help = "Gradient shading (the transfer function's lighting).",
                 .read = [](const D& d) { return boolText(d.transferFunction.shading.enabled); },
                 .write = [](D& d, sv v) { d.transferFunction.shading.enabled = isTrue(v); }});
    t.push_back({.name = "leaping",
                 .words = "empty-space leaping",
                 .kind = OptionKind::Switch,
                 .cliFlag = "no-leaping",
                 .cliSets = "false",
                 .wireMessage = kWireSampling,
                 .wireKey = "leaping",
                 .help = "Skip bricks that are empty under the transfer function.",
                 .read = [](const D& d) { return boolText(d.sampling.emptySpaceLeaping); },
                 .write = [](D& d, sv v) { d.sampling.emptySpaceLeaping = isTrue(v); }});
    t.push_back(
        {.name = "precision",
         .words = "precision",
         .kind = OptionKind::Choice,
         .choices = {"float", "double"},
         .cliFlag = "precision",
         .valueName = "NAME",
         .wireMessage = kWireSampling,
         .wireKey = "precision",
         .help = "CPU arithmetic: float (fast, tabulated transfer function) or double "
                 "(the reference).",
         .read = [](const D& d) { return std::string(precisionName(d.sampling.precision)); },
         .write =
             [](D& d, sv v) {
                 d.sampling.precision = v == "double" ? Precision::Double : Precision::Float;
             }});
    t.push_back({.name = "early-termination",
                 .words = "early termination",
                 .kind = OptionKind::Number,
                 .min = kTiny,
                 .max = 1.0,
                 .cliFlag = "early-termination",
                 .valueName = "ALPHA",
                 .wireMessage = kWireSampling,
                 .wireKey = "early_termination",
                 .help = "A ray stops when its opacity reaches this.",
                 .read = [](const D& d) { return number(d.sampling.earlyTermination); },
                 .write = [](D& d, sv v) { d.sampling.earlyTermination = parseNumber(v); }});
    t.push_back({.name = "brick",
                 .words = "brick size",
                 .kind = OptionKind::Integer,
                 .min = 1,
                 .max = 4096,
                 .cliFlag = "brick",
                 .valueName = "N",
                 .help = "Brick size in voxels (bricks are what leaping skips and the GPU pool "
                         "holds).",
                 .read = [](const D& d) { return std::to_string(d.sampling.brickSize); },
                 .write = [](D& d, sv v) { d.sampling.brickSize = int(parseNumber(v)); }});
    return t;
}

const std::vector<RenderOption>& table() {
    static const std::vector<RenderOption> options = makeTable();
    return options;
}

std::string rangeText(const RenderOption& o) {
    const auto bound = [](double v) {
        return v >= kHuge    ? std::string("inf")
               : v <= -kHuge ? std::string("-inf")
               : v == kTiny  ? std::string("0 (exclusive)")
                             : number(v);
    };
    return bound(o.min) + " to " + bound(o.max);
}

void checkValue(const RenderOption& o, double v) {
    if (!std::isfinite(v) || v < o.min || v > o.max) {
        throw std::invalid_argument(std::string(o.words) + " " + number(v) + " is out of range (" +
                                    rangeText(o) + ")");
    }
    if (o.kind == OptionKind::Integer && v != std::floor(v)) {
        throw std::invalid_argument(std::string(o.words) + " " + number(v) +
                                    " must be a whole number");
    }
}

} // namespace

std::span<const RenderOption> renderOptions() {
    return table();
}

const RenderOption* findRenderOption(std::string_view name) {
    for (const RenderOption& o : table()) {
        if (o.name == name || (!o.cliFlag.empty() && o.cliFlag == name)) {
            return &o;
        }
    }
    return nullptr;
}

std::pair<int, int> parseImageSize(std::string_view text) {
    const std::size_t x = text.find('x');
    int w = 0, h = 0;
    const auto whole = [](std::string_view s, int& out) {
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
        return ec == std::errc() && end == s.data() + s.size() && !s.empty();
    };
    if (x == std::string_view::npos || !whole(text.substr(0, x), w) ||
        !whole(text.substr(x + 1), h)) {
        throw std::invalid_argument("image size '" + std::string(text) + "' is not WIDTHxHEIGHT");
    }
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide) {
        throw std::invalid_argument("image size " + std::string(text) + " is out of range (1 to " +
                                    std::to_string(kMaxImageSide) + " per side)");
    }
    return {w, h};
}

ClipBox parseClipBox(std::string_view text) {
    if (text == "all") {
        return ClipBox{};
    }
    double v[6] = {};
    std::size_t at = 0;
    for (int n = 0; n < 6; ++n) {
        const std::size_t comma = n < 5 ? text.find(',', at) : text.size();
        if (comma == std::string_view::npos) {
            throw std::invalid_argument("clip box '" + std::string(text) +
                                        "' is not X0,Y0,Z0,X1,Y1,Z1 or all");
        }
        try {
            v[n] = parseNumber(text.substr(at, comma - at));
        } catch (const std::invalid_argument&) {
            throw std::invalid_argument("clip box '" + std::string(text) +
                                        "' is not X0,Y0,Z0,X1,Y1,Z1 or all");
        }
        if (!std::isfinite(v[n])) {
            throw std::invalid_argument("clip box '" + std::string(text) + "' is not finite");
        }
        at = comma + 1;
    }
    const ClipBox box{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    if (glm::any(glm::greaterThan(box.lo, box.hi))) {
        throw std::invalid_argument("clip box '" + std::string(text) +
                                    "': a first corner's coordinate exceeds the second's");
    }
    return box;
}

std::string clipBoxText(const ClipBox& box) {
    const ClipBox all;
    if (box.lo == all.lo && box.hi == all.hi) {
        return "all";
    }
    return number(box.lo.x) + "," + number(box.lo.y) + "," + number(box.lo.z) + "," +
           number(box.hi.x) + "," + number(box.hi.y) + "," + number(box.hi.z);
}

void applyRenderOption(RenderDescription& description, const RenderOption& option,
                       std::string_view text) {
    switch (option.kind) {
    case OptionKind::Number:
    case OptionKind::Integer: {
        double v = 0.0;
        try {
            v = parseNumber(text);
        } catch (const std::invalid_argument&) {
            throw std::invalid_argument(std::string(option.name) + ": '" + std::string(text) +
                                        "' is not a number");
        }
        checkValue(option, v);
        break;
    }
    case OptionKind::Choice: {
        bool known = false;
        for (const std::string_view c : option.choices) {
            known = known || c == text;
        }
        if (!known) {
            throw std::invalid_argument(std::string(option.name) + ": '" + std::string(text) +
                                        "' is not one of " + choiceText(option.choices));
        }
        break;
    }
    case OptionKind::Switch:
        if (text != "true" && text != "false") {
            throw std::invalid_argument(std::string(option.name) + ": '" + std::string(text) +
                                        "' is not true or false");
        }
        break;
    case OptionKind::Size:
        parseImageSize(text); // throws with the reason
        break;
    case OptionKind::Box:
        parseClipBox(text); // throws with the reason
        break;
    }
    option.write(description, text);
}

std::string renderOptionValue(const RenderDescription& description, const RenderOption& option) {
    return option.read(description);
}

std::string renderOptionDefault(const RenderOption& option) {
    return option.read(RenderDescription{});
}

void checkRenderOptionRanges(const RenderDescription& d) {
    if (d.width < 1 || d.height < 1 || d.width > kMaxImageSide || d.height > kMaxImageSide) {
        throw std::invalid_argument("image size " + std::to_string(d.width) + "x" +
                                    std::to_string(d.height) + " is out of range (1 to " +
                                    std::to_string(kMaxImageSide) + " per side)");
    }
    for (const RenderOption& o : table()) {
        if (o.kind == OptionKind::Number || o.kind == OptionKind::Integer) {
            const std::string text = o.read(d);
            checkValue(o, parseNumber(text));
        }
    }
}

std::string renderOptionsMarkdown() {
    std::string md = "| option | command line | wire | kind | range or choices | default | "
                     "what it does |\n|---|---|---|---|---|---|---|\n";
    for (const RenderOption& o : table()) {
        std::string cli = o.cliFlag.empty() ? "" : "`--" + std::string(o.cliFlag);
        if (!o.cliFlag.empty()) {
            cli += o.cliSets.empty() ? " " + std::string(o.valueName) + "`"
                                     : "` (sets " + std::string(o.cliSets) + ")";
        }
        const std::string wire = o.wireMessage.empty() ? ""
                                                       : "`" + std::string(o.wireMessage) + "." +
                                                             std::string(o.wireKey) + "`";
        std::string kind, range;
        switch (o.kind) {
        case OptionKind::Number:
            kind = "number";
            range = rangeText(o);
            break;
        case OptionKind::Integer:
            kind = "integer";
            range = rangeText(o);
            break;
        case OptionKind::Choice:
            kind = "choice";
            range = choiceText(o.choices);
            break;
        case OptionKind::Switch:
            kind = "switch";
            range = "true, false";
            break;
        case OptionKind::Size:
            kind = "WxH";
            range = "1 to " + std::to_string(kMaxImageSide) + " per side";
            break;
        case OptionKind::Box:
            kind = "box";
            range = "X0,Y0,Z0,X1,Y1,Z1 (voxels, X0 <= X1 ...) or all";
            break;
        }
        md += "| `" + std::string(o.name) + "` | " + cli + " | " + wire + " | " + kind + " | " +
              range + " | " + renderOptionDefault(o) + " | " + std::string(o.help) + " |\n";
    }
    return md;
}

} // namespace lucent
