// The view messages other than the options table's: tf, clip, quality, size,
// interaction.
#include <cmath>

#include <nlohmann/json.hpp>

#include "protocol/ClientMessageJson_p.h"
#include "protocol/JsonFields.h"

namespace lucent::remote {
namespace {

using Json = nlohmann::json;

glm::dvec3 vector3(const Json& value, const char* key) {
    if (!value.is_array() || value.size() != 3) {
        throwBadRequest(std::string("clip: '") + key + "' must be an array of three numbers");
    }
    glm::dvec3 v;
    for (int n = 0; n < 3; ++n) {
        if (!value[n].is_number() || !std::isfinite(value[n].get<double>())) {
            throwBadRequest(std::string("clip: '") + key + "' must be an array of three numbers");
        }
        v[n] = value[n].get<double>();
    }
    return v;
}

} // namespace

TransferFunctionUpdate parseTransferFunctionUpdate(const Json& m) {
    checkKeys(m, "tf", {"preset", "tf"});
    const bool hasPreset = m.contains("preset");
    if (hasPreset == m.contains("tf")) {
        throwBadRequest("tf: give exactly one of 'preset' and 'tf'");
    }
    TransferFunctionUpdate u;
    if (hasPreset) {
        u.preset = requiredString(m, "preset", "tf");
    } else {
        if (!m["tf"].is_object()) {
            throwBadRequest("tf: 'tf' must be a transfer-function object");
        }
        try {
            u.transferFunction = parseTransferFunction(m["tf"].dump(), "tf");
        } catch (const TransferFunctionError& e) {
            throwBadRequest(e.what());
        }
    }
    return u;
}

ClipUpdate parseClip(const Json& m) {
    checkKeys(m, "clip", {"lo", "hi"});
    ClipUpdate u;
    if (m.contains("lo")) {
        u.box.lo = vector3(m["lo"], "lo");
    }
    if (m.contains("hi")) {
        u.box.hi = vector3(m["hi"], "hi");
    }
    for (int n = 0; n < 3; ++n) {
        if (!(u.box.lo[n] <= u.box.hi[n])) {
            throwBadRequest("clip: 'lo' must not exceed 'hi'");
        }
    }
    return u;
}

QualityUpdate parseQuality(const Json& m) {
    checkKeys(m, "quality", {"quality"});
    const std::string name = requiredString(m, "quality", "quality");
    if (name == "interactive") {
        return {Quality::Interactive};
    }
    if (name == "still") {
        return {Quality::Still};
    }
    throwBadRequest("quality: '" + name + "' is not one of interactive, still");
}

SizeUpdate parseSize(const Json& m) {
    checkKeys(m, "size", {"width", "height"});
    SizeUpdate u;
    for (const auto& [key, target] : {std::pair{"width", &u.width}, {"height", &u.height}}) {
        const auto it = m.find(key);
        if (it == m.end() || !it->is_number_integer() || it->get<long long>() < kMinImageSide ||
            it->get<long long>() > kMaxImageSide) {
            throwBadRequest(std::string("size: '") + key + "' must be an integer from " +
                            std::to_string(kMinImageSide) + " to " + std::to_string(kMaxImageSide));
        }
        *target = it->get<int>();
    }
    return u;
}

InteractionUpdate parseInteraction(const Json& m) {
    checkKeys(m, "interaction", {"state"});
    const std::string state = requiredString(m, "state", "interaction");
    if (state != "start" && state != "end") {
        throwBadRequest("interaction: 'state' must be start or end");
    }
    return {state == "start"};
}

} // namespace lucent::remote
