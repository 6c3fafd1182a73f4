#include "core/scene/RenderDescriptionJson.h"

#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/scene/RenderOptions.h"

namespace lucent {
namespace {

using nlohmann::json;

json vec(const glm::dvec3& v) {
    return json::array({v.x, v.y, v.z});
}

glm::dvec3 vec(const json& j, const char* field) {
    if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() ||
        !j[2].is_number()) {
        throw std::invalid_argument(std::string("render description: '") + field +
                                    "' must be three numbers");
    }
    return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

const json& field(const json& j, const char* name) {
    const auto it = j.find(name);
    if (it == j.end()) {
        throw std::invalid_argument(std::string("render description: '") + name + "' is missing");
    }
    return *it;
}

} // namespace

std::string toJson(const RenderDescription& d) {
    json options = json::object();
    for (const RenderOption& option : renderOptions()) {
        options[std::string(option.name)] = renderOptionValue(d, option);
    }
    // dump() writes doubles in the shortest form that reads back exactly.
    return json{{"options", options},
                {"tf", toJson(d.transferFunction)},
                {"fov", d.camera.fieldOfView},
                {"background", vec(d.background)},
                {"simd", d.sampling.simd}}
        .dump();
}

RenderDescription parseRenderDescription(std::string_view text) {
    json j;
    try {
        j = json::parse(text);
    } catch (const json::parse_error& e) {
        throw std::invalid_argument(std::string("render description: ") + e.what());
    }
    if (!j.is_object()) {
        throw std::invalid_argument("render description: not a JSON object");
    }
    RenderDescription d;
    const json& tf = field(j, "tf");
    if (!tf.is_string()) {
        throw std::invalid_argument("render description: 'tf' must be a string");
    }
    d.transferFunction = parseTransferFunction(tf.get<std::string>(), "render description tf");
    // After the transfer function: the table's shading switch sets its shading.
    const json& options = field(j, "options");
    for (const RenderOption& option : renderOptions()) {
        const json& value = field(options, std::string(option.name).c_str());
        if (!value.is_string()) {
            throw std::invalid_argument("render description: option '" + std::string(option.name) +
                                        "' must be text");
        }
        applyRenderOption(d, option, value.get<std::string>());
    }
    const json& fov = field(j, "fov");
    if (!fov.is_number()) {
        throw std::invalid_argument("render description: 'fov' must be a number");
    }
    d.camera.fieldOfView = fov.get<double>();
    d.background = vec(field(j, "background"), "background");
    const json& simd = field(j, "simd");
    if (!simd.is_boolean()) {
        throw std::invalid_argument("render description: 'simd' must be true or false");
    }
    d.sampling.simd = simd.get<bool>();
    return d;
}

} // namespace lucent
