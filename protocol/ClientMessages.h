#pragma once
// The client's messages (docs/protocol.md, "Client messages") as C++ values. Their
// JSON has one reader and one writer (ClientMessageJson.h).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "core/scene/RenderDescription.h"
#include "core/tf/TransferFunction.h"
#include "protocol/MarkMessages.h"
#include "protocol/OptionValues.h"
#include "protocol/ProtocolVersion.h"
#include "protocol/SliceMessages.h"

namespace lucent::remote {

// Larger text messages are refused (an error, then the connection closes).
inline constexpr std::size_t kMaxMessageBytes = 64 * 1024;
// Frames are at least this and at most this wide and tall.
inline constexpr int kMinImageSide = 16;
inline constexpr int kMaxImageSide = 4096;
// An invite lives at most this long (and never past its session).
inline constexpr std::int64_t kMaxInviteLifetimeSeconds = 24 * 60 * 60;
// An invite code in `auth` is at most this long (the server's are 43 characters).
inline constexpr std::size_t kMaxInviteCodeBytes = 128;

enum class Quality { Interactive, Still };
const char* qualityName(Quality quality);

// Exactly one of the two: a token of the server's token file (a presenter's
// credential), or (version 3) an invite code, which joins its session as a follower.
struct AuthRequest {
    std::string token;
    std::string invite;
    bool operator==(const AuthRequest&) const = default;
};
struct ListRequest {
    bool operator==(const ListRequest&) const = default;
};
struct OpenRequest {
    std::string series; // a uid from the list reply
    bool operator==(const OpenRequest&) const = default;
};
// The camera options of the table (azimuth, elevation, zoom, distance, pan_right,
// pan_up); absent ones keep their value.
struct CameraUpdate : OptionUpdate {
    bool operator==(const CameraUpdate&) const = default;
};
// Exactly one of the two.
struct TransferFunctionUpdate {
    std::optional<std::string> preset;
    std::optional<TransferFunction> transferFunction;
    bool operator==(const TransferFunctionUpdate&) const = default;
};
// The mode options of the table: mode (required) and iso.
struct ModeUpdate : OptionUpdate {
    bool operator==(const ModeUpdate&) const = default;
};
struct ClipUpdate {
    ClipBox box; // voxel index coordinates; the default box clips nothing
    bool operator==(const ClipUpdate& other) const {
        return box.lo == other.box.lo && box.hi == other.box.hi;
    }
};
struct QualityUpdate {
    Quality quality = Quality::Still;
    bool operator==(const QualityUpdate&) const = default;
};
// Version 2: the sampling options of the table (step, interp, classification,
// preintegrate, shading, leaping, precision, early_termination); absent ones keep
// their value.
struct SamplingUpdate : OptionUpdate {
    bool operator==(const SamplingUpdate&) const = default;
};
struct SizeUpdate {
    int width = 0;
    int height = 0;
    bool operator==(const SizeUpdate&) const = default;
};
struct RenderRequest {
    bool operator==(const RenderRequest&) const = default;
};
// {"type":"interaction","state":"start"|"end"}: adaptive JPEG frames while
// active, one lossless still at the end.
struct InteractionUpdate {
    bool active = false;
    bool operator==(const InteractionUpdate&) const = default;
};
// Teaching sessions.
struct SessionCreate {
    bool operator==(const SessionCreate&) const = default;
};
struct SessionJoin {
    std::string session; // the id session-created gave
    bool operator==(const SessionJoin&) const = default;
};
struct SessionHandover {
    std::uint64_t to = 0; // a member number from session-state
    bool operator==(const SessionHandover&) const = default;
};
struct SessionLeave {
    bool operator==(const SessionLeave&) const = default;
};
// Version 3, the presenter of a session: an invite that lets its holder only
// follow the session. `lifetime` (seconds, 1..kMaxInviteLifetimeSeconds): absent,
// it lives as long as the session, at most a day. `origin` ("https://host:port"):
// what the link starts with; absent, the host this client reached the server by.
struct InviteCreate {
    std::optional<std::int64_t> lifetimeSeconds;
    std::optional<std::string> origin;
    bool operator==(const InviteCreate&) const = default;
};
struct InviteRevoke {
    std::uint64_t invite = 0; // the number invite-created gave
    bool operator==(const InviteRevoke&) const = default;
};
// Version 4, a follower of a session: {"type":"free-look","state":"start"|"end"}:
// its own view of the session's series (its camera, the presenter's look), or
// back to the session's view.
struct FreeLook {
    bool active = false;
    bool operator==(const FreeLook&) const = default;
};
// Version 4, the presenter: every follower in free look back to the session's view.
struct FreeLookRecall {
    bool operator==(const FreeLookRecall&) const = default;
};

// Version 4, recording and replay (protocol/Recording.h): {"type":"record",
// "state":"start"|"stop"}; the store's recordings; a recording replayed into the
// client's view (or its session), at the pace it was recorded or a view a step.
struct RecordRequest {
    bool start = true;
    bool operator==(const RecordRequest&) const = default;
};
struct RecordingListRequest {
    bool operator==(const RecordingListRequest&) const = default;
};
enum class ReplayPace { Original, Step };
const char* replayPaceName(ReplayPace pace);
// A recording's id is at most this long, of letters, digits, '-' and '_'.
inline constexpr std::size_t kMaxRecordingIdBytes = 64;
struct ReplayRequest {
    std::string recording; // an id from recording-started or recordings
    ReplayPace pace = ReplayPace::Original;
    bool operator==(const ReplayRequest&) const = default;
};
struct ReplayStep {
    bool operator==(const ReplayStep&) const = default;
};
struct ReplayStop {
    bool operator==(const ReplayStop&) const = default;
};

using ClientMessage =
    std::variant<AuthRequest, ListRequest, OpenRequest, CameraUpdate, TransferFunctionUpdate,
                 ModeUpdate, ClipUpdate, QualityUpdate, SamplingUpdate, SizeUpdate, RenderRequest,
                 InteractionUpdate, SessionCreate, SessionJoin, SessionHandover, SessionLeave,
                 InviteCreate, InviteRevoke, PointerUpdate, MarkPlace, MarksClear, FreeLook,
                 FreeLookRecall, SlicesRequest, RecordRequest, RecordingListRequest, ReplayRequest,
                 ReplayStep, ReplayStop>;

// True for the messages that change a view (and owe a frame).
bool isViewMessage(const ClientMessage& message);
// Its `type` on the wire ("camera", "session-join", ...).
std::string_view messageType(const ClientMessage& message);
// The protocol version that brought this type of message ("sampling": 2); 0 for a
// type no version has.
int messageTypeVersion(std::string_view type);
int messageVersion(const ClientMessage& message);

} // namespace lucent::remote
