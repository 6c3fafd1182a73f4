#pragma once
// Lucent remote render protocol, version 1 (docs/protocol.md): the client's
// JSON control messages, the server's JSON replies, and the binary frame
// layout. Plain C++ (no Qt), so that the parser can be tested on its own.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>

#include "core/scene/RenderDescription.h"
#include "core/tf/TransferFunction.h"

namespace lucent::remote {

inline constexpr int kProtocolVersion = 1;
// Larger text messages are refused (an error, then the connection closes).
inline constexpr std::size_t kMaxMessageBytes = 64 * 1024;
// Frames are at most this wide and tall.
inline constexpr int kMaxImageSide = 4096;

enum class Quality { Interactive, Still };
const char* qualityName(Quality quality);

struct AuthRequest {
    std::string token;
};
struct ListRequest {};
struct OpenRequest {
    std::string series; // a uid from the list reply
};
// Absent fields keep their value.
struct CameraUpdate {
    std::optional<double> azimuth;
    std::optional<double> elevation;
    std::optional<double> zoom;
    std::optional<double> distance; // mm from the eye to the centre; 0: fit the volume
    std::optional<double> panRight; // mm, the view centre moved along the screen's right
    std::optional<double> panUp;    // mm, along the screen's up
};
// Camera distance and pan lie within these (mm).
inline constexpr double kMaxCameraDistance = 100000.0;
inline constexpr double kMaxCameraPan = 100000.0;
// Exactly one of the two.
struct TransferFunctionUpdate {
    std::optional<std::string> preset;
    std::optional<TransferFunction> transferFunction;
};
struct ModeUpdate {
    RenderMode mode = RenderMode::Dvr;
    std::optional<double> isoValue;
};
struct ClipUpdate {
    ClipBox box; // voxel index coordinates; the default box clips nothing
};
struct QualityUpdate {
    Quality quality = Quality::Still;
};
struct SizeUpdate {
    int width = 0;
    int height = 0;
};
struct RenderRequest {};
// {"type":"interaction","state":"start"|"end"}: adaptive JPEG frames while
// active, one lossless still at the end.
struct InteractionUpdate {
    bool active = false;
};
// Teaching sessions.
struct SessionCreate {};
struct SessionJoin {
    std::string session; // the id session-created gave
};
struct SessionHandover {
    std::uint64_t to = 0; // a member number from session-state
};
struct SessionLeave {};

using ClientMessage =
    std::variant<AuthRequest, ListRequest, OpenRequest, CameraUpdate, TransferFunctionUpdate,
                 ModeUpdate, ClipUpdate, QualityUpdate, SizeUpdate, RenderRequest,
                 InteractionUpdate, SessionCreate, SessionJoin, SessionHandover, SessionLeave>;

// True for the messages that change a view (and owe a frame).
bool isViewMessage(const ClientMessage& message);

// Why a message was refused. `code` is one of the codes in docs/protocol.md;
// fatal errors end the connection after the error message is sent.
class ProtocolError : public std::runtime_error {
public:
    ProtocolError(std::string code, const std::string& message, bool fatal)
        : std::runtime_error(message), code_(std::move(code)), fatal_(fatal) {}
    const std::string& code() const { return code_; }
    bool fatal() const { return fatal_; }

private:
    std::string code_;
    bool fatal_;
};

// Parses one text message. Throws ProtocolError: "too-large", "malformed" and
// "unknown-type" are fatal; "bad-request" (a field missing, of the wrong type
// or out of range) is not.
ClientMessage parseClientMessage(std::string_view text);

// {"type":"error","code":...,"message":...,"fatal":...}
std::string errorReply(std::string_view code, std::string_view message, bool fatal);

// What precedes the image bytes of a binary frame.
struct FrameHeader {
    int width = 0;
    int height = 0;
    std::string format; // "png" or "jpeg"
    std::uint64_t seq = 0;
    Quality quality = Quality::Still;
    double renderMs = 0.0;
    double encodeMs = 0.0;
    // Interactive frames: the image scale against the view's size (1, 0.75,
    // 0.5 or 0.35) and the JPEG quality (60..85); 1 and 0 for PNG stills.
    double scale = 1.0;
    int jpegQuality = 0;
};

// A binary frame: 4 bytes big-endian header length N, N bytes of header JSON,
// then the encoded image.
std::string frameMessage(const FrameHeader& header, std::string_view imageBytes);

// The inverse of frameMessage (for clients and tests). Throws ProtocolError
// ("malformed", fatal) when the layout or the header is wrong.
struct ParsedFrame {
    FrameHeader header;
    std::string_view image; // points into the message
};
ParsedFrame parseFrameMessage(std::string_view message);

} // namespace lucent::remote
