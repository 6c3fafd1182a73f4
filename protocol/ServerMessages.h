#pragma once
// The server's JSON messages (docs/protocol.md, "Server messages") as C++ values,
// with their one writer (the server) and one reader (clients and tests).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

#include "protocol/ClientMessages.h"
#include "protocol/MarkMessages.h"
#include "protocol/ProtocolError.h"
#include "protocol/ProtocolVersion.h"
#include "protocol/QrCode.h"
#include "protocol/SliceMessages.h"

namespace lucent::remote {

// After authentication: the version this connection speaks and what renders.
struct Hello {
    int version = kProtocolVersion;
    std::string backend; // "cpu", "gl: <renderer>, <version>"
    // Version 4: the MPR window presets a client may name in `slices` (none before).
    std::vector<WindowPresetInfo> windowPresets;
    bool operator==(const Hello&) const = default;
};
// One series of the `series` reply (never a patient's name, id or birth date).
struct SeriesSummary {
    std::string uid;
    std::string description; // empty for a session's follower
    std::string modality;
    glm::ivec3 dims{0};
    bool operator==(const SeriesSummary&) const = default;
};
struct SeriesListReply {
    std::vector<SeriesSummary> series;
    bool operator==(const SeriesListReply&) const = default;
};
struct Opened {
    std::string series;
    glm::ivec3 dims{0};
    double radiusMm = 0.0; // the volume's bounding sphere, which zoom 1 fits
    std::string preset;
    // Version 4: the volume's centre (LPS mm), where MPR slices start their crosshair.
    std::optional<glm::dvec3> centre;
    bool operator==(const Opened&) const = default;
};
struct ErrorReply {
    std::string code;
    std::string message;
    bool fatal = false;
    bool operator==(const ErrorReply&) const = default;
};
struct SessionCreated {
    std::string session;
    bool operator==(const SessionCreated&) const = default;
};
struct SessionState {
    std::string session;
    int members = 0;
    std::vector<std::uint64_t> memberIds;
    std::optional<std::uint64_t> presenter; // none while the session hands over
    std::uint64_t you = 0;
    std::string role;                  // "presenter" or "follower"
    std::optional<std::string> series; // the shown series' uid
    bool operator==(const SessionState&) const = default;
};
struct SessionLeft {
    std::string session;
    bool operator==(const SessionLeft&) const = default;
};

// Version 3: an invite to the presenter's session. The code is the secret; the
// number names it (invite-revoke). `path` is the join link without the origin
// ("/#invite=CODE": the code rides in the fragment, which no request carries),
// `link` the whole link, `qr` the QR code of `link`.
struct InviteCreated {
    std::uint64_t invite = 0;
    std::string code;
    std::int64_t expires = 0; // seconds since 1970-01-01 UTC
    std::string path;
    std::string link;
    QrCode qr;
    bool operator==(const InviteCreated&) const = default;
};
struct InviteRevoked {
    std::uint64_t invite = 0;
    bool operator==(const InviteRevoked&) const = default;
};

// Version 4, free look. To the follower: its own view starts (its frames follow,
// the first numbered `seq`; its camera as the session's was, in the keys of the
// `camera` message), or it ends (`reason`: own, recalled, series,
// presenting, left, session-ended) and the session's newest frame follows.
struct FreeLookStarted {
    std::uint64_t seq = 0;
    double azimuth = 0.0, elevation = 0.0, zoom = 1.0, distance = 0.0, panRight = 0.0, panUp = 0.0;
    bool operator==(const FreeLookStarted&) const = default;
};
struct FreeLookEnded {
    std::string reason;
    bool operator==(const FreeLookEnded&) const = default;
};
// To the presenter: how many followers look on their own, of at most `limit`.
struct FreeLookState {
    int looking = 0;
    int limit = 0;
    bool operator==(const FreeLookState&) const = default;
};
// Version 4, recording and replay (protocol/Recording.h). `views` counts the
// recorded views: the view when recording began and each change of it after.
// `reason`: why a recording stopped ("stopped", "limit", "view": the view it
// recorded went away) or a replay ended ("end", "stopped", "view": the client
// took the view back, opened a series or changed its session).
struct RecordingStarted {
    std::string recording;
    bool operator==(const RecordingStarted&) const = default;
};
struct RecordingStopped {
    std::string recording;
    int views = 0;
    std::int64_t durationMs = 0;
    std::string reason;
    bool operator==(const RecordingStopped&) const = default;
};
struct RecordingSummary {
    std::string id;
    std::string series; // the series as the server lists it (never a de-identified copy's)
    std::int64_t durationMs = 0;
    int views = 0;
    std::int64_t created = 0; // ms since 1970-01-01 UTC
    bool operator==(const RecordingSummary&) const = default;
};
struct RecordingList {
    std::vector<RecordingSummary> recordings; // newest first
    bool operator==(const RecordingList&) const = default;
};
// A replay shows recorded view `view` (0..views-1) in the frame numbered `seq`.
struct ReplayProgress {
    std::string recording;
    int view = 0;
    int views = 0;
    std::uint64_t seq = 0;
    bool operator==(const ReplayProgress&) const = default;
};
// `camera`: the view's camera when the replay ended (the camera message's
// keys), so that a client that keeps its own camera goes on from there.
struct ReplayEnded {
    std::string recording;
    std::string reason;
    CameraUpdate camera;
    bool operator==(const ReplayEnded&) const = default;
};

using ServerMessage =
    std::variant<Hello, SeriesListReply, Opened, ErrorReply, SessionCreated, SessionState,
                 SessionLeft, InviteCreated, InviteRevoked, PointerShown, MarkShown, MarksCleared,
                 FreeLookStarted, FreeLookEnded, FreeLookState, RecordingStarted, RecordingStopped,
                 RecordingList, ReplayProgress, ReplayEnded>;

// The hello of a connection that speaks `version`: from version 4 with the MPR window presets.
Hello helloFor(int version, std::string backend);

// The message as compact JSON.
std::string writeServerMessage(const ServerMessage& message);
// Reads one text message of the server. Fields it does not know are ignored (a
// newer server may add some). Throws ProtocolError: "malformed" (fatal) when it is
// not JSON or a field is missing or of the wrong type; "unknown-type" (not fatal:
// a client skips it) for a type it does not know.
ServerMessage parseServerMessage(std::string_view text);

// {"type":"error","code":...,"message":...,"fatal":...}
std::string errorReply(std::string_view code, std::string_view message, bool fatal);

} // namespace lucent::remote
