#include "protocol/SliceMessageJson_p.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "core/mpr/WindowPresets.h"
#include "protocol/ClientMessages.h"
#include "protocol/ProtocolError.h"

namespace lucent::remote {
namespace {

using Json = nlohmann::json;

constexpr Orientation kViews[] = {Orientation::Axial, Orientation::Coronal, Orientation::Sagittal};

std::string where(const char* key) {
    return std::string("slices: '") + key + "'";
}

double boundedNumber(const Json& value, const std::string& name, double lo, double hi) {
    if (!value.is_number() || !std::isfinite(value.get<double>()) || value.get<double>() < lo ||
        value.get<double>() > hi) {
        throwBadRequest(name + " must be a number from " + std::to_string(lo) + " to " +
                        std::to_string(hi));
    }
    return value.get<double>();
}

glm::dvec3 readCrosshair(const Json& value) {
    if (!value.is_array() || value.size() != 3) {
        throwBadRequest(where("crosshair") + " must be [x, y, z] (LPS mm)");
    }
    glm::dvec3 p;
    for (int a = 0; a < 3; ++a) {
        p[a] = boundedNumber(value[std::size_t(a)], where("crosshair"), -kMaxSliceCoordinate,
                             kMaxSliceCoordinate);
    }
    return p;
}

void readWindow(const Json& value, SlicesRequest& r) {
    if (value.is_string()) {
        const std::string name = value.get<std::string>();
        if (!findWindowPreset(name)) {
            std::string names;
            for (const WindowPreset& p : windowPresets()) {
                names += (names.empty() ? "" : ", ") + std::string(p.name);
            }
            throwBadRequest(where("window") + ": no window preset '" + name.substr(0, 64) + "' (" +
                            names + ")");
        }
        r.windowPreset = name;
        return;
    }
    if (!value.is_object()) {
        throwBadRequest(where("window") +
                        " must be {\"center\": C, \"width\": W} or a preset name");
    }
    for (const auto& [key, item] : value.items()) {
        if (key != "center" && key != "width") {
            throwBadRequest(where("window") + ": unknown field '" + key.substr(0, 64) + "'");
        }
    }
    if (!value.contains("center") || !value.contains("width")) {
        throwBadRequest(where("window") + " needs both 'center' and 'width'");
    }
    r.window = SliceWindow{
        boundedNumber(value["center"], where("window") + ".center", -kMaxSliceCoordinate,
                      kMaxSliceCoordinate),
        boundedNumber(value["width"], where("window") + ".width", 0.0, kMaxSliceCoordinate)};
}

glm::ivec2 readSize(const Json& value) {
    const std::string what = where("size") + " must be [width, height], integers from " +
                             std::to_string(kMinImageSide) + " to " + std::to_string(kMaxSliceSide);
    if (!value.is_array() || value.size() != 2) {
        throwBadRequest(what);
    }
    glm::ivec2 size;
    for (int a = 0; a < 2; ++a) {
        const Json& side = value[std::size_t(a)];
        if (!side.is_number_integer() || side.get<long long>() < kMinImageSide ||
            side.get<long long>() > kMaxSliceSide) {
            throwBadRequest(what);
        }
        size[a] = side.get<int>();
    }
    return size;
}

std::vector<Orientation> readViews(const Json& value) {
    const std::string what =
        where("views") + " must be a list of distinct views: axial, coronal, sagittal";
    if (!value.is_array() || value.size() > 3) {
        throwBadRequest(what);
    }
    std::vector<Orientation> views;
    for (const Json& item : value) {
        const auto view = item.is_string() ? sliceViewNamed(item.get<std::string>()) : std::nullopt;
        if (!view || std::find(views.begin(), views.end(), *view) != views.end()) {
            throwBadRequest(what);
        }
        views.push_back(*view);
    }
    return views;
}

Json vec3(const glm::dvec3& p) {
    return Json::array({p.x, p.y, p.z});
}

glm::dvec3 readVec3(const Json& j) {
    if (!j.is_array() || j.size() != 3) {
        throw std::invalid_argument("a point must hold three numbers");
    }
    return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

} // namespace

std::string_view sliceViewName(Orientation view) {
    switch (view) {
    case Orientation::Axial:
        return "axial";
    case Orientation::Coronal:
        return "coronal";
    case Orientation::Sagittal:
        return "sagittal";
    }
    return "axial";
}

std::optional<Orientation> sliceViewNamed(std::string_view name) {
    for (const Orientation view : kViews) {
        if (sliceViewName(view) == name) {
            return view;
        }
    }
    return std::nullopt;
}

std::vector<WindowPresetInfo> windowPresetInfos() {
    std::vector<WindowPresetInfo> infos;
    for (const WindowPreset& p : windowPresets()) {
        infos.push_back({std::string(p.name), p.center, p.width});
    }
    return infos;
}

SlicesRequest parseSlicesRequest(const Json& m) {
    static const std::set<std::string> known{"type", "crosshair", "window", "size", "views"};
    for (const auto& [key, value] : m.items()) {
        if (!known.count(key)) {
            throwBadRequest("slices: unknown field '" + key.substr(0, 64) + "'");
        }
    }
    SlicesRequest r;
    if (m.contains("crosshair")) {
        r.crosshair = readCrosshair(m["crosshair"]);
    }
    if (m.contains("window")) {
        readWindow(m["window"], r);
    }
    if (m.contains("size")) {
        r.size = readSize(m["size"]);
    }
    if (m.contains("views")) {
        r.views = readViews(m["views"]);
    }
    return r;
}

void writeSlicesRequest(Json& m, const SlicesRequest& r) {
    if (r.crosshair) {
        m["crosshair"] = vec3(*r.crosshair);
    }
    if (r.windowPreset) {
        m["window"] = *r.windowPreset;
    } else if (r.window) {
        m["window"] = {{"center", r.window->center}, {"width", r.window->width}};
    }
    if (r.size) {
        m["size"] = {r.size->x, r.size->y};
    }
    if (r.views) {
        Json views = Json::array();
        for (const Orientation view : *r.views) {
            views.push_back(std::string(sliceViewName(view)));
        }
        m["views"] = views;
    }
}

void writeSliceFrameInfo(Json& header, const SliceFrameInfo& info) {
    header["view"] = std::string(sliceViewName(info.view));
    header["crosshair"] = vec3(info.crosshair);
    header["window"] = {{"center", info.window.center}, {"width", info.window.width}};
    header["plane"] = {{"centre", vec3(info.centre)},
                       {"u", vec3(info.u)},
                       {"v", vec3(info.v)},
                       {"pixel_mm", info.pixelMm},
                       {"step_mm", info.stepMm}};
}

SliceFrameInfo readSliceFrameInfo(const Json& header) {
    SliceFrameInfo info;
    const auto view = sliceViewNamed(header.at("view").get<std::string>());
    if (!view) {
        throw std::invalid_argument("'view' must be axial, coronal or sagittal");
    }
    info.view = *view;
    info.crosshair = readVec3(header.at("crosshair"));
    const Json& window = header.at("window");
    info.window = {window.at("center").get<double>(), window.at("width").get<double>()};
    const Json& plane = header.at("plane");
    info.centre = readVec3(plane.at("centre"));
    info.u = readVec3(plane.at("u"));
    info.v = readVec3(plane.at("v"));
    info.pixelMm = plane.at("pixel_mm").get<double>();
    info.stepMm = plane.at("step_mm").get<double>();
    return info;
}

Json windowPresetsJson(const std::vector<WindowPresetInfo>& presets) {
    Json list = Json::array();
    for (const WindowPresetInfo& p : presets) {
        list.push_back({{"name", p.name}, {"center", p.center}, {"width", p.width}});
    }
    return list;
}

std::vector<WindowPresetInfo> readWindowPresets(const Json& presets) {
    std::vector<WindowPresetInfo> list;
    for (const Json& p : presets) {
        list.push_back({p.at("name").get<std::string>(), p.at("center").get<double>(),
                        p.at("width").get<double>()});
    }
    return list;
}

} // namespace lucent::remote
