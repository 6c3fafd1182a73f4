// The render options' table: one row per option, and the look-ups into it.
#include "core/scene/RenderOptions.h"

#include <stdexcept>

#include "core/scene/RenderOptions_p.h"

// Each row names only the fields it sets (designated initializers); the rest
// keep their defaults, which GCC's -Wextra would report one by one.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace lucent {
namespace {

using detail::kHuge;
using detail::kTiny;
using detail::number;
using detail::parseNumber;

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

// Image size, clip box, mode and iso value.
void addViewRows(std::vector<RenderOption>& t) {
    using D = RenderDescription;
    using sv = std::string_view;
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
}

// The camera's angles, zoom, distance and pan.
void addCameraRows(std::vector<RenderOption>& t) {
    using D = RenderDescription;
    using sv = std::string_view;
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
}

// How the rays sample: step, interpolation, classification, pre-integration.
void addSamplingRows(std::vector<RenderOption>& t) {
    using D = RenderDescription;
    using sv = std::string_view;
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
}

// What the caster does along a ray: shading, leaping, precision, early
// termination, bricks.
void addCastingRows(std::vector<RenderOption>& t) {
    using D = RenderDescription;
    using sv = std::string_view;
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
    t.push_back({.name = "leap-distance",
                 .words = "leaping by distance map",
                 .kind = OptionKind::Switch,
                 .cliFlag = "no-leap-distance",
                 .cliSets = "false",
                 .help = "GL: a leap crosses every empty cell within a distance map's reach at "
                         "once, not one cell (the same image).",
                 .read = [](const D& d) { return boolText(d.sampling.leapDistance); },
                 .write = [](D& d, sv v) { d.sampling.leapDistance = isTrue(v); }});
    t.push_back({.name = "block-skipping",
                 .words = "block skipping",
                 .kind = OptionKind::Switch,
                 .cliFlag = "no-block-skipping",
                 .cliSets = "false",
                 .help = "GL, DVR (post-classified, trilinear or nearest): pass over the samples "
                         "of 2x2x2-voxel blocks that show nothing without reading the volume (the "
                         "same image).",
                 .read = [](const D& d) { return boolText(d.sampling.blockSkipping); },
                 .write = [](D& d, sv v) { d.sampling.blockSkipping = isTrue(v); }});
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
                         "holds; the GPU takes at most 1023).",
                 .read = [](const D& d) { return std::to_string(d.sampling.brickSize); },
                 .write = [](D& d, sv v) { d.sampling.brickSize = int(parseNumber(v)); }});
}

// The overlay of a fused render (RenderOverlay): its colour map, window and opacity. The
// overlay volume itself comes with the description (lucent-cli render --overlay PATH).
void addOverlayRows(std::vector<RenderOption>& t) {
    using D = RenderDescription;
    using sv = std::string_view;
    t.push_back(
        {.name = "overlay-map",
         .words = "overlay colour map",
         .kind = OptionKind::Choice,
         .choices = {"grey", "hot-iron", "rainbow", "pet"},
         .cliFlag = "overlay-map",
         .valueName = "MAP",
         .help = "The overlay's colour map (with --overlay).",
         .read = [](const D& d) { return std::string(colourMapName(d.overlay.style.colourMap)); },
         .write =
             [](D& d, sv v) {
                 d.overlay.style.colourMap =
                     colourMapFromName(v).value_or(FusionColourMap::HotIron);
             }});
    t.push_back(
        {.name = "overlay-window",
         .words = "overlay window",
         .kind = OptionKind::Window,
         .cliFlag = "overlay-window",
         .valueName = "C,W",
         .help = "The overlay's window (centre, width, in its own units): its colour map "
                 "spans it and its opacity rises from 0 at the low end to the overlay "
                 "opacity at the high end; auto: L 40 W 400 for CT, else its 1st to 99th "
                 "percentile.",
         .read =
             [](const D& d) { return windowText(d.overlay.style.center, d.overlay.style.width); },
         .write =
             [](D& d, sv v) {
                 std::tie(d.overlay.style.center, d.overlay.style.width) = parseWindow(v);
             }});
    t.push_back({.name = "overlay-opacity",
                 .words = "overlay opacity",
                 .kind = OptionKind::Number,
                 .min = 0.0,
                 .max = 1.0,
                 .cliFlag = "overlay-opacity",
                 .valueName = "A",
                 .help = "The overlay's opacity at the top of its window (per voxel in DVR; "
                         "over the base's projection in MIP, MinIP and average); 0 shows the "
                         "base alone.",
                 .read = [](const D& d) { return number(d.overlay.style.opacity); },
                 .write = [](D& d, sv v) { d.overlay.style.opacity = parseNumber(v); }});
}

// One row per option; `read` and `write` reach its field.
std::vector<RenderOption> makeTable() {
    std::vector<RenderOption> t;
    addViewRows(t);
    addCameraRows(t);
    addSamplingRows(t);
    addCastingRows(t);
    addOverlayRows(t);
    return t;
}

} // namespace

const std::vector<RenderOption>& detail::table() {
    static const std::vector<RenderOption> options = makeTable();
    return options;
}

std::span<const RenderOption> renderOptions() {
    return detail::table();
}

const RenderOption* findRenderOption(std::string_view name) {
    for (const RenderOption& o : detail::table()) {
        if (o.name == name || (!o.cliFlag.empty() && o.cliFlag == name)) {
            return &o;
        }
    }
    return nullptr;
}

} // namespace lucent
