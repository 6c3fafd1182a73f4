#include "protocol/ClientMessageJson.h"

#include <type_traits>

#include <nlohmann/json.hpp>

#include "protocol/ClientMessageJson_p.h"
#include "protocol/JsonFields.h"
#include "protocol/MarkMessageJson.h"
#include "protocol/RecordingMessageJson_p.h"
#include "protocol/SliceMessageJson_p.h"

namespace lucent::remote {
namespace {

using Json = nlohmann::json;

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
