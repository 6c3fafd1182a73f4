#include "protocol/ServerMessages.h"

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "protocol/ClientMessageJson.h"
#include "protocol/JsonIntegers.h"
#include "protocol/MarkMessageJson.h"
#include "protocol/SliceMessageJson_p.h"

namespace lucent::remote {
namespace {

using Json = nlohmann::json;

Json dims(const glm::ivec3& d) {
    return Json::array({d.x, d.y, d.z});
}

glm::ivec3 readDims(const Json& j) {
    if (!j.is_array() || j.size() != 3) {
        throw ProtocolError("malformed", "'dims' must hold three integers", true);
    }
    return {jsonInteger<int>(j[0], "dims"), jsonInteger<int>(j[1], "dims"),
            jsonInteger<int>(j[2], "dims")};
}

template <class T> Json optional(const std::optional<T>& v) {
    return v ? Json(*v) : Json();
}

template <class T> std::optional<T> readOptional(const Json& m, const char* key) {
    const Json& v = m.at(key);
    if (v.is_null()) {
        return std::nullopt;
    }
    if constexpr (std::is_integral_v<T>) {
        return jsonInteger<T>(v, key);
    } else {
        return v.get<T>();
    }
}

// {"size":N,"rows":["1110...", ...]}: a row a string of 0 (light) and 1 (dark).
Json qrJson(const QrCode& qr) {
    Json rows = Json::array();
    for (int y = 0; y < qr.size; ++y) {
        std::string row(std::size_t(qr.size), '0');
        for (int x = 0; x < qr.size; ++x) {
            row[std::size_t(x)] = qr.dark(x, y) ? '1' : '0';
        }
        rows.push_back(std::move(row));
    }
    return {{"size", qr.size}, {"rows", rows}};
}

QrCode readQr(const Json& j) {
    QrCode qr;
    qr.size = jsonInteger<int>(j.at("size"), "qr.size");
    const Json& rows = j.at("rows");
    if (qr.size < 0 || qr.size > 177 || !rows.is_array() || rows.size() != std::size_t(qr.size)) {
        throw ProtocolError("malformed", "'qr' must hold 'size' rows of 'size' modules", true);
    }
    for (const Json& row : rows) {
        const std::string text = row.get<std::string>();
        if (text.size() != std::size_t(qr.size) ||
            text.find_first_not_of("01") != std::string::npos) {
            throw ProtocolError("malformed", "a 'qr' row must hold 'size' of 0 and 1", true);
        }
        for (const char c : text) {
            qr.modules.push_back(c == '1' ? 1 : 0);
        }
    }
    return qr;
}

// A camera as the camera message's keys, written and read by that message's
// own writer and reader.
Json cameraJson(const CameraUpdate& camera) {
    Json j = Json::parse(writeClientMessage(camera));
    j.erase("type");
    return j;
}

CameraUpdate readCamera(const Json& j) {
    if (!j.is_object()) {
        throw ProtocolError("malformed", "'camera' must be an object", true);
    }
    Json message = j;
    message["type"] = "camera";
    try {
        return std::get<CameraUpdate>(parseClientMessage(message.dump()));
    } catch (const ProtocolError& e) {
        throw ProtocolError("malformed", std::string("'camera': ") + e.what(), true);
    }
}

struct Writer {
    Json operator()(const Hello& h) const {
        Json m = {{"type", "hello"}, {"version", h.version}, {"backend", h.backend}};
        if (!h.windowPresets.empty()) {
            m["window_presets"] = windowPresetsJson(h.windowPresets);
        }
        return m;
    }
    Json operator()(const SeriesListReply& l) const {
        Json list = Json::array();
        for (const SeriesSummary& s : l.series) {
            list.push_back({{"uid", s.uid},
                            {"description", s.description},
                            {"modality", s.modality},
                            {"dims", dims(s.dims)}});
        }
        return {{"type", "series"}, {"series", list}};
    }
    Json operator()(const Opened& o) const {
        Json m = {{"type", "opened"},
                  {"series", o.series},
                  {"dims", dims(o.dims)},
                  {"radius_mm", o.radiusMm},
                  {"preset", o.preset}};
        if (o.centre) {
            m["centre"] = {o.centre->x, o.centre->y, o.centre->z};
        }
        return m;
    }
    Json operator()(const ErrorReply& e) const {
        return {{"type", "error"}, {"code", e.code}, {"message", e.message}, {"fatal", e.fatal}};
    }
    Json operator()(const SessionCreated& c) const {
        return {{"type", "session-created"}, {"session", c.session}};
    }
    Json operator()(const SessionState& s) const {
        return {{"type", "session-state"},
                {"session", s.session},
                {"members", s.members},
                {"member_ids", s.memberIds},
                {"presenter", optional(s.presenter)},
                {"you", s.you},
                {"role", s.role},
                {"series", optional(s.series)}};
    }
    Json operator()(const SessionLeft& l) const {
        return {{"type", "session-left"}, {"session", l.session}};
    }
    Json operator()(const InviteCreated& c) const {
        return {{"type", "invite-created"}, {"invite", c.invite}, {"code", c.code},
                {"expires", c.expires},     {"path", c.path},     {"link", c.link},
                {"qr", qrJson(c.qr)}};
    }
    Json operator()(const InviteRevoked& r) const {
        return {{"type", "invite-revoked"}, {"invite", r.invite}};
    }
    Json operator()(const PointerShown& p) const { return pointerShownJson(p); }
    Json operator()(const MarkShown& m) const { return markShownJson(m); }
    Json operator()(const MarksCleared&) const { return {{"type", "marks-cleared"}}; }
    Json operator()(const FreeLookStarted& s) const {
        return {{"type", "free-look-started"},
                {"seq", s.seq},
                {"camera",
                 {{"azimuth", s.azimuth},
                  {"elevation", s.elevation},
                  {"zoom", s.zoom},
                  {"distance", s.distance},
                  {"pan_right", s.panRight},
                  {"pan_up", s.panUp}}}};
    }
    Json operator()(const FreeLookEnded& e) const {
        return {{"type", "free-look-ended"}, {"reason", e.reason}};
    }
    Json operator()(const FreeLookState& s) const {
        return {{"type", "free-look-state"}, {"looking", s.looking}, {"limit", s.limit}};
    }
    Json operator()(const RecordingStarted& r) const {
        return {{"type", "recording-started"}, {"recording", r.recording}};
    }
    Json operator()(const RecordingStopped& r) const {
        return {{"type", "recording-stopped"},
                {"recording", r.recording},
                {"views", r.views},
                {"duration_ms", r.durationMs},
                {"reason", r.reason}};
    }
    Json operator()(const RecordingList& l) const {
        Json list = Json::array();
        for (const RecordingSummary& r : l.recordings) {
            list.push_back({{"id", r.id},
                            {"series", r.series},
                            {"duration_ms", r.durationMs},
                            {"views", r.views},
                            {"created", r.created}});
        }
        return {{"type", "recordings"}, {"recordings", list}};
    }
    Json operator()(const ReplayProgress& p) const {
        return {{"type", "replay-progress"},
                {"recording", p.recording},
                {"view", p.view},
                {"views", p.views},
                {"seq", p.seq}};
    }
    Json operator()(const ReplayEnded& e) const {
        return {{"type", "replay-ended"},
                {"recording", e.recording},
                {"reason", e.reason},
                {"camera", cameraJson(e.camera)}};
    }
};

// A teaching session's messages: the session, invites, pointer and marks, free look.
std::optional<ServerMessage> readSessionMessage(const Json& m, const std::string& type) {
    if (type == "session-created") {
        return SessionCreated{m.at("session").get<std::string>()};
    }
    if (type == "session-state") {
        std::vector<std::uint64_t> memberIds;
        if (!m.at("member_ids").is_array()) {
            throw ProtocolError("malformed", "'member_ids' must be an array of integers", true);
        }
        for (const Json& id : m.at("member_ids")) {
            memberIds.push_back(jsonInteger<std::uint64_t>(id, "member_ids"));
        }
        return SessionState{m.at("session").get<std::string>(),
                            jsonInteger<int>(m.at("members"), "members"),
                            std::move(memberIds),
                            readOptional<std::uint64_t>(m, "presenter"),
                            jsonInteger<std::uint64_t>(m.at("you"), "you"),
                            m.at("role").get<std::string>(),
                            readOptional<std::string>(m, "series")};
    }
    if (type == "session-left") {
        return SessionLeft{m.at("session").get<std::string>()};
    }
    if (type == "invite-created") {
        return InviteCreated{jsonInteger<std::uint64_t>(m.at("invite"), "invite"),
                             m.at("code").get<std::string>(),
                             jsonInteger<std::int64_t>(m.at("expires"), "expires"),
                             m.at("path").get<std::string>(),
                             m.at("link").get<std::string>(),
                             readQr(m.at("qr"))};
    }
    if (type == "invite-revoked") {
        return InviteRevoked{jsonInteger<std::uint64_t>(m.at("invite"), "invite")};
    }
    if (type == "pointer") {
        return readPointerShown(m);
    }
    if (type == "mark") {
        return readMarkShown(m);
    }
    if (type == "marks-cleared") {
        return MarksCleared{};
    }
    if (type == "free-look-started") {
        const Json& c = m.at("camera");
        return FreeLookStarted{jsonInteger<std::uint64_t>(m.at("seq"), "seq"),
                               c.at("azimuth").get<double>(),
                               c.at("elevation").get<double>(),
                               c.at("zoom").get<double>(),
                               c.at("distance").get<double>(),
                               c.at("pan_right").get<double>(),
                               c.at("pan_up").get<double>()};
    }
    if (type == "free-look-ended") {
        return FreeLookEnded{m.at("reason").get<std::string>()};
    }
    if (type == "free-look-state") {
        return FreeLookState{jsonInteger<int>(m.at("looking"), "looking"),
                             jsonInteger<int>(m.at("limit"), "limit")};
    }
    return std::nullopt;
}

// Recordings and their replay.
std::optional<ServerMessage> readRecordingMessage(const Json& m, const std::string& type) {
    if (type == "recording-started") {
        return RecordingStarted{m.at("recording").get<std::string>()};
    }
    if (type == "recording-stopped") {
        return RecordingStopped{m.at("recording").get<std::string>(),
                                jsonInteger<int>(m.at("views"), "views"),
                                jsonInteger<std::int64_t>(m.at("duration_ms"), "duration_ms"),
                                m.at("reason").get<std::string>()};
    }
    if (type == "recordings") {
        RecordingList l;
        for (const Json& r : m.at("recordings")) {
            l.recordings.push_back({r.at("id").get<std::string>(),
                                    r.at("series").get<std::string>(),
                                    jsonInteger<std::int64_t>(r.at("duration_ms"), "duration_ms"),
                                    jsonInteger<int>(r.at("views"), "views"),
                                    jsonInteger<std::int64_t>(r.at("created"), "created")});
        }
        return l;
    }
    if (type == "replay-progress") {
        return ReplayProgress{m.at("recording").get<std::string>(),
                              jsonInteger<int>(m.at("view"), "view"),
                              jsonInteger<int>(m.at("views"), "views"),
                              jsonInteger<std::uint64_t>(m.at("seq"), "seq")};
    }
    if (type == "replay-ended") {
        return ReplayEnded{m.at("recording").get<std::string>(), m.at("reason").get<std::string>(),
                           m.contains("camera") ? readCamera(m.at("camera")) : CameraUpdate{}};
    }
    return std::nullopt;
}

ServerMessage read(const Json& m, const std::string& type) {
    if (type == "hello") {
        return Hello{jsonInteger<int>(m.at("version"), "version"),
                     m.at("backend").get<std::string>(),
                     m.contains("window_presets") ? readWindowPresets(m.at("window_presets"))
                                                  : std::vector<WindowPresetInfo>{}};
    }
    if (type == "series") {
        SeriesListReply l;
        for (const Json& s : m.at("series")) {
            l.series.push_back({s.at("uid").get<std::string>(),
                                s.value("description", std::string()),
                                s.at("modality").get<std::string>(), readDims(s.at("dims"))});
        }
        return l;
    }
    if (type == "opened") {
        Opened o{m.at("series").get<std::string>(), readDims(m.at("dims")),
                 m.value("radius_mm", 0.0), m.value("preset", std::string()), std::nullopt};
        if (m.contains("centre")) {
            const Json& c = m.at("centre");
            o.centre =
                glm::dvec3(c.at(0).get<double>(), c.at(1).get<double>(), c.at(2).get<double>());
        }
        return o;
    }
    if (type == "error") {
        return ErrorReply{m.at("code").get<std::string>(), m.at("message").get<std::string>(),
                          m.at("fatal").get<bool>()};
    }
    if (std::optional<ServerMessage> session = readSessionMessage(m, type)) {
        return std::move(*session);
    }
    if (std::optional<ServerMessage> recording = readRecordingMessage(m, type)) {
        return std::move(*recording);
    }
    throw ProtocolError("unknown-type", "unknown server message type '" + type.substr(0, 64) + "'",
                        false);
}

} // namespace

std::string writeServerMessage(const ServerMessage& message) {
    return std::visit(Writer{}, message).dump();
}

Hello helloFor(int version, std::string backend) {
    return Hello{version, std::move(backend),
                 version >= 4 ? windowPresetInfos() : std::vector<WindowPresetInfo>{}};
}

ServerMessage parseServerMessage(std::string_view text) {
    const Json m = Json::parse(text, nullptr, false);
    if (m.is_discarded() || !m.is_object() || !m.contains("type") || !m["type"].is_string()) {
        throw ProtocolError("malformed", "a server message must be a JSON object with a 'type'",
                            true);
    }
    const std::string type = m["type"].get<std::string>();
    try {
        return read(m, type);
    } catch (const Json::exception& e) {
        throw ProtocolError("malformed", type + ": " + e.what(), true);
    }
}

std::string errorReply(std::string_view code, std::string_view message, bool fatal) {
    return writeServerMessage(ErrorReply{std::string(code), std::string(message), fatal});
}

} // namespace lucent::remote
