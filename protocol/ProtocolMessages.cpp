#include "protocol/ProtocolMessages.h"

#include <cmath>
#include <set>

#include <nlohmann/json.hpp>

namespace lucent::remote {
namespace {

using Json = nlohmann::json;

[[noreturn]] void badRequest(const std::string& message) {
    throw ProtocolError("bad-request", message, false);
}

// Every key of `object` must be one of `known` ("type" always is).
void checkKeys(const Json& object, const std::string& type, std::set<std::string> known) {
    known.insert("type");
    for (const auto& [key, value] : object.items()) {
        if (!known.count(key)) {
            badRequest(type + ": unknown field '" + key + "'");
        }
    }
}

std::optional<double> optionalNumber(const Json& object, const char* key, const std::string& type) {
    const auto it = object.find(key);
    if (it == object.end()) {
        return std::nullopt;
    }
    if (!it->is_number() || !std::isfinite(it->get<double>())) {
        badRequest(type + ": '" + key + "' must be a finite number");
    }
    return it->get<double>();
}

std::string requiredString(const Json& object, const char* key, const std::string& type) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_string() || it->get<std::string>().empty()) {
        badRequest(type + ": '" + key + "' must be a non-empty string");
    }
    return it->get<std::string>();
}

glm::dvec3 vector3(const Json& value, const char* key) {
    if (!value.is_array() || value.size() != 3) {
        badRequest(std::string("clip: '") + key + "' must be an array of three numbers");
    }
    glm::dvec3 v;
    for (int n = 0; n < 3; ++n) {
        if (!value[n].is_number() || !std::isfinite(value[n].get<double>())) {
            badRequest(std::string("clip: '") + key + "' must be an array of three numbers");
        }
        v[n] = value[n].get<double>();
    }
    return v;
}

CameraUpdate parseCamera(const Json& m) {
    checkKeys(m, "camera", {"azimuth", "elevation", "zoom", "distance", "pan_right", "pan_up"});
    CameraUpdate c{
        optionalNumber(m, "azimuth", "camera"),   optionalNumber(m, "elevation", "camera"),
        optionalNumber(m, "zoom", "camera"),      optionalNumber(m, "distance", "camera"),
        optionalNumber(m, "pan_right", "camera"), optionalNumber(m, "pan_up", "camera")};
    if (c.zoom && !(*c.zoom > 0.01 && *c.zoom < 100.0)) {
        badRequest("camera: 'zoom' must lie between 0.01 and 100");
    }
    if (c.distance && !(*c.distance >= 0.0 && *c.distance <= kMaxCameraDistance)) {
        badRequest("camera: 'distance' must lie between 0 (fit the volume) and 100000 mm");
    }
    for (const auto& [pan, key] :
         {std::pair{c.panRight, "pan_right"}, std::pair{c.panUp, "pan_up"}}) {
        if (pan && !(std::abs(*pan) <= kMaxCameraPan)) {
            badRequest(std::string("camera: '") + key + "' must lie between -100000 and 100000 mm");
        }
    }
    return c;
}

TransferFunctionUpdate parseTransferFunctionUpdate(const Json& m) {
    checkKeys(m, "tf", {"preset", "tf"});
    const bool hasPreset = m.contains("preset");
    if (hasPreset == m.contains("tf")) {
        badRequest("tf: give exactly one of 'preset' and 'tf'");
    }
    TransferFunctionUpdate u;
    if (hasPreset) {
        u.preset = requiredString(m, "preset", "tf");
    } else {
        if (!m["tf"].is_object()) {
            badRequest("tf: 'tf' must be a transfer-function object");
        }
        try {
            u.transferFunction = parseTransferFunction(m["tf"].dump(), "tf");
        } catch (const TransferFunctionError& e) {
            badRequest(e.what());
        }
    }
    return u;
}

ModeUpdate parseMode(const Json& m) {
    checkKeys(m, "mode", {"mode", "iso"});
    const std::string name = requiredString(m, "mode", "mode");
    ModeUpdate u;
    if (name == "dvr") {
        u.mode = RenderMode::Dvr;
    } else if (name == "mip") {
        u.mode = RenderMode::Mip;
    } else if (name == "minip") {
        u.mode = RenderMode::MinIp;
    } else if (name == "avg") {
        u.mode = RenderMode::Average;
    } else if (name == "iso") {
        u.mode = RenderMode::Isosurface;
    } else {
        badRequest("mode: '" + name + "' is not one of dvr, mip, minip, avg, iso");
    }
    u.isoValue = optionalNumber(m, "iso", "mode");
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
            badRequest("clip: 'lo' must not exceed 'hi'");
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
    badRequest("quality: '" + name + "' is not one of interactive, still");
}

SizeUpdate parseSize(const Json& m) {
    checkKeys(m, "size", {"width", "height"});
    SizeUpdate u;
    for (const auto& [key, target] : {std::pair{"width", &u.width}, {"height", &u.height}}) {
        const auto it = m.find(key);
        if (it == m.end() || !it->is_number_integer() || it->get<long long>() < 16 ||
            it->get<long long>() > kMaxImageSide) {
            badRequest(std::string("size: '") + key + "' must be an integer from 16 to " +
                       std::to_string(kMaxImageSide));
        }
        *target = it->get<int>();
    }
    return u;
}

InteractionUpdate parseInteraction(const Json& m) {
    checkKeys(m, "interaction", {"state"});
    const std::string state = requiredString(m, "state", "interaction");
    if (state != "start" && state != "end") {
        badRequest("interaction: 'state' must be start or end");
    }
    return {state == "start"};
}

SessionJoin parseSessionJoin(const Json& m) {
    checkKeys(m, "session-join", {"session"});
    std::string id = requiredString(m, "session", "session-join");
    if (id.size() > 64) {
        badRequest("session-join: 'session' is longer than 64 characters");
    }
    return {std::move(id)};
}

SessionHandover parseSessionHandover(const Json& m) {
    checkKeys(m, "session-handover", {"to"});
    const auto it = m.find("to");
    if (it == m.end() || !it->is_number_unsigned() || it->get<std::uint64_t>() == 0) {
        badRequest("session-handover: 'to' must be a member number from session-state");
    }
    return {it->get<std::uint64_t>()};
}

} // namespace

bool isViewMessage(const ClientMessage& message) {
    return std::holds_alternative<CameraUpdate>(message) ||
           std::holds_alternative<TransferFunctionUpdate>(message) ||
           std::holds_alternative<ModeUpdate>(message) ||
           std::holds_alternative<ClipUpdate>(message) ||
           std::holds_alternative<QualityUpdate>(message) ||
           std::holds_alternative<SizeUpdate>(message) ||
           std::holds_alternative<RenderRequest>(message) ||
           std::holds_alternative<InteractionUpdate>(message);
}

const char* qualityName(Quality quality) {
    return quality == Quality::Interactive ? "interactive" : "still";
}

ClientMessage parseClientMessage(std::string_view text) {
    if (text.size() > kMaxMessageBytes) {
        throw ProtocolError("too-large",
                            "message of " + std::to_string(text.size()) + " bytes exceeds " +
                                std::to_string(kMaxMessageBytes),
                            true);
    }
    const Json m = Json::parse(text, nullptr, false);
    if (m.is_discarded()) {
        throw ProtocolError("malformed", "message is not valid JSON", true);
    }
    if (!m.is_object() || !m.contains("type") || !m["type"].is_string()) {
        throw ProtocolError("malformed", "message must be a JSON object with a string 'type'",
                            true);
    }
    const std::string type = m["type"].get<std::string>();
    if (type == "auth") {
        checkKeys(m, type, {"token"});
        return AuthRequest{requiredString(m, "token", type)};
    }
    if (type == "list") {
        checkKeys(m, type, {});
        return ListRequest{};
    }
    if (type == "open") {
        checkKeys(m, type, {"series"});
        return OpenRequest{requiredString(m, "series", type)};
    }
    if (type == "camera") {
        return parseCamera(m);
    }
    if (type == "tf") {
        return parseTransferFunctionUpdate(m);
    }
    if (type == "mode") {
        return parseMode(m);
    }
    if (type == "clip") {
        return parseClip(m);
    }
    if (type == "quality") {
        return parseQuality(m);
    }
    if (type == "size") {
        return parseSize(m);
    }
    if (type == "render") {
        checkKeys(m, type, {});
        return RenderRequest{};
    }
    if (type == "interaction") {
        return parseInteraction(m);
    }
    if (type == "session-create") {
        checkKeys(m, type, {});
        return SessionCreate{};
    }
    if (type == "session-join") {
        return parseSessionJoin(m);
    }
    if (type == "session-handover") {
        return parseSessionHandover(m);
    }
    if (type == "session-leave") {
        checkKeys(m, type, {});
        return SessionLeave{};
    }
    throw ProtocolError("unknown-type", "unknown message type '" + type.substr(0, 64) + "'", true);
}

std::string errorReply(std::string_view code, std::string_view message, bool fatal) {
    return Json{{"type", "error"}, {"code", code}, {"message", message}, {"fatal", fatal}}.dump();
}

std::string frameMessage(const FrameHeader& header, std::string_view imageBytes) {
    const std::string json = Json{
        {"width", header.width},
        {"height", header.height},
        {"format", header.format},
        {"seq", header.seq},
        {"quality", qualityName(header.quality)},
        {"render_ms", header.renderMs},
        {"encode_ms", header.encodeMs},
        {"scale", header.scale},
        {"jpeg_quality",
         header.jpegQuality}}.dump();
    const auto n = static_cast<std::uint32_t>(json.size());
    std::string out;
    out.reserve(4 + json.size() + imageBytes.size());
    for (int shift : {24, 16, 8, 0}) {
        out.push_back(static_cast<char>((n >> shift) & 0xffu));
    }
    out += json;
    out += imageBytes;
    return out;
}

ParsedFrame parseFrameMessage(std::string_view message) {
    auto malformed = [](const std::string& why) {
        return ProtocolError("malformed", "frame: " + why, true);
    };
    if (message.size() < 4) {
        throw malformed("shorter than its length field");
    }
    std::uint32_t n = 0;
    for (int i = 0; i < 4; ++i) {
        n = (n << 8) | static_cast<unsigned char>(message[static_cast<std::size_t>(i)]);
    }
    if (n > message.size() - 4) {
        throw malformed("header length exceeds the message");
    }
    const Json h = Json::parse(message.substr(4, n), nullptr, false);
    if (h.is_discarded() || !h.is_object()) {
        throw malformed("header is not a JSON object");
    }
    ParsedFrame f;
    try {
        f.header.width = h.at("width").get<int>();
        f.header.height = h.at("height").get<int>();
        f.header.format = h.at("format").get<std::string>();
        f.header.seq = h.at("seq").get<std::uint64_t>();
        f.header.quality = h.at("quality").get<std::string>() == "interactive"
                               ? Quality::Interactive
                               : Quality::Still;
        f.header.renderMs = h.value("render_ms", 0.0);
        f.header.encodeMs = h.value("encode_ms", 0.0);
        f.header.scale = h.value("scale", 1.0);
        f.header.jpegQuality = h.value("jpeg_quality", 0);
    } catch (const Json::exception& e) {
        throw malformed(std::string("header: ") + e.what());
    }
    f.image = message.substr(4 + n);
    return f;
}

} // namespace lucent::remote
