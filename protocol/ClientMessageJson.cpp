#include "protocol/ClientMessageJson.h"

#include <charconv>
#include <cmath>
#include <set>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "protocol/JsonFields.h"
#include "protocol/MarkMessageJson.h"
#include "protocol/RecordingMessageJson_p.h"
#include "protocol/SliceMessageJson_p.h"

namespace lucent::remote {
namespace {

using Json = nlohmann::json;

// --- camera, mode, sampling: the options table ----------------------------------

// The keys a message of options must hold.
std::set<std::string> requiredOptionKeys(std::string_view type) {
    return type == "mode" ? std::set<std::string>{"mode"} : std::set<std::string>{};
}

std::string shortest(double v) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
    return std::string(buffer, result.ptr);
}

std::string choicesText(const RenderOption& o) {
    std::string text;
    for (const std::string_view c : o.choices) {
        text += (text.empty() ? "" : ", ") + std::string(c);
    }
    return text;
}

// The JSON value as the table's text: numbers for Number and Integer options,
// strings for Choice, true/false for Switch.
std::string optionText(const Json& value, const RenderOption& o, const std::string& type) {
    const std::string where = type + ": '" + std::string(o.wireKey) + "'";
    switch (o.kind) {
    case OptionKind::Number:
    case OptionKind::Integer:
        if (!value.is_number() || !std::isfinite(value.get<double>())) {
            throwBadRequest(where + " must be a finite number");
        }
        return value.is_number_integer() ? std::to_string(value.get<long long>())
                                         : shortest(value.get<double>());
    case OptionKind::Choice:
        if (!value.is_string()) {
            throwBadRequest(where + " must be one of " + choicesText(o) + " (a string)");
        }
        return value.get<std::string>();
    case OptionKind::Switch:
        if (!value.is_boolean()) {
            throwBadRequest(where + " must be true or false");
        }
        return value.get<bool>() ? "true" : "false";
    case OptionKind::Size:
    case OptionKind::Box:
        break;
    }
    throw std::logic_error("the image size and clip box travel in their own messages, not " + type);
}

Json optionJson(const OptionValue& v) {
    const std::string& t = v.text;
    switch (v.option->kind) {
    case OptionKind::Number: {
        double d = 0.0;
        std::from_chars(t.data(), t.data() + t.size(), d);
        return d;
    }
    case OptionKind::Integer: {
        long long n = 0;
        std::from_chars(t.data(), t.data() + t.size(), n);
        return n;
    }
    case OptionKind::Choice:
        return t;
    case OptionKind::Switch:
        return t == "true";
    case OptionKind::Size:
    case OptionKind::Box:
        break;
    }
    throw std::logic_error("the image size and clip box travel in their own messages");
}

OptionUpdate parseOptions(const Json& m, const std::string& type) {
    const std::vector<const RenderOption*> rows = wireOptions(type);
    std::set<std::string> known;
    for (const RenderOption* o : rows) {
        known.insert(std::string(o->wireKey));
    }
    checkKeys(m, type, known);
    for (const std::string& key : requiredOptionKeys(type)) {
        if (!m.contains(key)) {
            throwBadRequest(type + ": '" + key + "' is missing");
        }
    }
    OptionUpdate update;
    for (const RenderOption* o : rows) {
        const auto it = m.find(std::string(o->wireKey));
        if (it != m.end()) {
            update.values.push_back(checkedOptionValue(type, *o, optionText(*it, *o, type)));
        }
    }
    return update;
}

void writeOptions(Json& m, const OptionUpdate& update) {
    for (const OptionValue& v : update.values) {
        m[std::string(v.option->wireKey)] = optionJson(v);
    }
}

// --- the other messages -----------------------------------------------------------

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

FreeLook parseFreeLook(const Json& m) {
    checkKeys(m, "free-look", {"state"});
    const std::string state = requiredString(m, "state", "free-look");
    if (state != "start" && state != "end") {
        throwBadRequest("free-look: 'state' must be start or end");
    }
    return {state == "start"};
}

SessionJoin parseSessionJoin(const Json& m) {
    checkKeys(m, "session-join", {"session"});
    std::string id = requiredString(m, "session", "session-join");
    if (id.size() > 64) {
        throwBadRequest("session-join: 'session' is longer than 64 characters");
    }
    return {std::move(id)};
}

SessionHandover parseSessionHandover(const Json& m) {
    checkKeys(m, "session-handover", {"to"});
    const auto it = m.find("to");
    if (it == m.end() || !it->is_number_unsigned() || it->get<std::uint64_t>() == 0) {
        throwBadRequest("session-handover: 'to' must be a member number from session-state");
    }
    return {it->get<std::uint64_t>()};
}

AuthRequest parseAuth(const Json& m, int version) {
    if (version < 3 && m.contains("invite")) {
        // Before version 3 an unknown field; an invite holder learns what it needs.
        throw ProtocolError("auth-failed",
                            "an invite needs protocol version 3 (offer the subprotocol lucent.v3); "
                            "this connection speaks version " +
                                std::to_string(version),
                            true);
    }
    if (version < 3) {
        checkKeys(m, "auth", {"token"});
        return {requiredString(m, "token", "auth"), {}};
    }
    checkKeys(m, "auth", {"token", "invite"});
    if (m.contains("token") == m.contains("invite")) {
        throwBadRequest("auth: give exactly one of 'token' and 'invite'");
    }
    if (m.contains("token")) {
        return {requiredString(m, "token", "auth"), {}};
    }
    std::string invite = requiredString(m, "invite", "auth");
    if (invite.size() > kMaxInviteCodeBytes) {
        throwBadRequest("auth: 'invite' is longer than " + std::to_string(kMaxInviteCodeBytes) +
                        " characters");
    }
    return {{}, std::move(invite)};
}

// "http(s)://host[:port]": letters, digits and . - : [ ] after the scheme.
bool isOrigin(std::string_view origin) {
    for (const std::string_view scheme : {"https://", "http://"}) {
        if (origin.starts_with(scheme)) {
            const std::string_view rest = origin.substr(scheme.size());
            return !rest.empty() && rest.size() <= 253 + 6 &&
                   rest.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                          "0123456789.-:[]") == std::string_view::npos;
        }
    }
    return false;
}

InviteCreate parseInviteCreate(const Json& m) {
    checkKeys(m, "invite-create", {"lifetime", "origin"});
    InviteCreate c;
    if (const auto it = m.find("lifetime"); it != m.end()) {
        if (!it->is_number_integer() || it->get<long long>() < 1 ||
            it->get<long long>() > kMaxInviteLifetimeSeconds) {
            throwBadRequest("invite-create: 'lifetime' must be an integer number of seconds from "
                            "1 to " +
                            std::to_string(kMaxInviteLifetimeSeconds));
        }
        c.lifetimeSeconds = it->get<std::int64_t>();
    }
    if (m.contains("origin")) {
        c.origin = requiredString(m, "origin", "invite-create");
        if (!isOrigin(*c.origin)) {
            throwBadRequest("invite-create: 'origin' must be http(s)://HOST[:PORT], without a "
                            "path");
        }
    }
    return c;
}

InviteRevoke parseInviteRevoke(const Json& m) {
    checkKeys(m, "invite-revoke", {"invite"});
    const auto it = m.find("invite");
    if (it == m.end() || !it->is_number_unsigned() || it->get<std::uint64_t>() == 0) {
        throwBadRequest("invite-revoke: 'invite' must be the number invite-created gave");
    }
    return {it->get<std::uint64_t>()};
}

template <class T> T empty(const Json& m, const std::string& type) {
    checkKeys(m, type, {});
    return T{};
}

ClientMessage parseTyped(const Json& m, const std::string& type, int version) {
    if (type == "auth") {
        return parseAuth(m, version);
    }
    if (type == "invite-create") {
        return parseInviteCreate(m);
    }
    if (type == "invite-revoke") {
        return parseInviteRevoke(m);
    }
    if (type == "pointer") {
        return parsePointerUpdate(m);
    }
    if (type == "mark") {
        return parseMarkPlace(m);
    }
    if (type == "marks-clear") {
        return empty<MarksClear>(m, type);
    }
    if (type == "slices") {
        return parseSlicesRequest(m);
    }
    if (type == "open") {
        checkKeys(m, type, {"series"});
        return OpenRequest{requiredString(m, "series", type)};
    }
    if (type == "camera") {
        return CameraUpdate{parseOptions(m, type)};
    }
    if (type == "mode") {
        return ModeUpdate{parseOptions(m, type)};
    }
    if (type == "sampling") {
        return SamplingUpdate{parseOptions(m, type)};
    }
    if (type == "tf") {
        return parseTransferFunctionUpdate(m);
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
    if (type == "interaction") {
        return parseInteraction(m);
    }
    if (type == "free-look") {
        return parseFreeLook(m);
    }
    if (type == "free-look-recall") {
        return empty<FreeLookRecall>(m, type);
    }
    if (type == "session-join") {
        return parseSessionJoin(m);
    }
    if (type == "session-handover") {
        return parseSessionHandover(m);
    }
    if (auto recording = parseRecordingMessage(m, type)) {
        return std::move(*recording);
    }
    if (type == "list") {
        return empty<ListRequest>(m, type);
    }
    if (type == "render") {
        return empty<RenderRequest>(m, type);
    }
    if (type == "session-create") {
        return empty<SessionCreate>(m, type);
    }
    if (type == "session-leave") {
        return empty<SessionLeave>(m, type);
    }
    throw std::logic_error("parseClientMessage: type '" + type + "' has no reader");
}

// The fields of each message (everything but "type").
struct FieldWriter {
    Json& m;
    void operator()(const AuthRequest& a) const {
        if (!a.invite.empty()) {
            m["invite"] = a.invite;
        } else {
            m["token"] = a.token;
        }
    }
    void operator()(const InviteCreate& c) const {
        if (c.lifetimeSeconds) {
            m["lifetime"] = *c.lifetimeSeconds;
        }
        if (c.origin) {
            m["origin"] = *c.origin;
        }
    }
    void operator()(const InviteRevoke& r) const { m["invite"] = r.invite; }
    void operator()(const PointerUpdate& p) const { writePointerUpdate(m, p); }
    void operator()(const MarkPlace& p) const { writeMarkPlace(m, p); }
    void operator()(const OpenRequest& o) const { m["series"] = o.series; }
    void operator()(const SlicesRequest& r) const { writeSlicesRequest(m, r); }
    void operator()(const OptionUpdate& u) const { writeOptions(m, u); }
    void operator()(const TransferFunctionUpdate& u) const {
        if (u.preset) {
            m["preset"] = *u.preset;
        } else if (u.transferFunction) {
            m["tf"] = Json::parse(toJson(*u.transferFunction));
        }
    }
    void operator()(const ClipUpdate& u) const {
        const ClipBox none;
        if (u.box.lo != none.lo) {
            m["lo"] = {u.box.lo.x, u.box.lo.y, u.box.lo.z};
        }
        if (u.box.hi != none.hi) {
            m["hi"] = {u.box.hi.x, u.box.hi.y, u.box.hi.z};
        }
    }
    void operator()(const QualityUpdate& u) const { m["quality"] = qualityName(u.quality); }
    void operator()(const SizeUpdate& u) const {
        m["width"] = u.width;
        m["height"] = u.height;
    }
    void operator()(const InteractionUpdate& u) const { m["state"] = u.active ? "start" : "end"; }
    void operator()(const FreeLook& f) const { m["state"] = f.active ? "start" : "end"; }
    void operator()(const SessionJoin& j) const { m["session"] = j.session; }
    void operator()(const SessionHandover& h) const { m["to"] = h.to; }
    void operator()(const RecordRequest& r) const { m["state"] = r.start ? "start" : "stop"; }
    void operator()(const ReplayRequest& r) const {
        m["recording"] = r.recording;
        m["pace"] = replayPaceName(r.pace);
    }
    // list, render, session-create, session-leave: the type alone.
    template <class T>
    requires std::is_empty_v<T>
    void operator()(const T&) const {}
};

} // namespace

ClientMessage parseClientMessage(std::string_view text, int version) {
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
    const int since = messageTypeVersion(type);
    if (since == 0) {
        throw ProtocolError("unknown-type", "unknown message type '" + type.substr(0, 64) + "'",
                            true);
    }
    if (since > version) {
        throw ProtocolError("unknown-type",
                            "unknown message type '" + type + "' in protocol version " +
                                std::to_string(version) + " (it came with version " +
                                std::to_string(since) + ")",
                            true);
    }
    return parseTyped(m, type, version);
}

std::string writeClientMessage(const ClientMessage& message) {
    Json m = Json::object();
    m["type"] = std::string(messageType(message));
    std::visit(FieldWriter{m}, message);
    return m.dump();
}

} // namespace lucent::remote
