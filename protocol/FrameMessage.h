#pragma once
// The binary frame message (docs/protocol.md, "Frames"): 4 bytes big-endian header
// length N, N bytes of header JSON, then the encoded image.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "protocol/ClientMessages.h"
#include "protocol/ProtocolError.h"
#include "protocol/SliceMessages.h"

namespace lucent::remote {

// What precedes the image bytes.
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
    // Version 4 servers: the 3 x 4 row-major matrix taking (x, y, z, 1) in LPS mm
    // to (u w, v w, w), u and v fractions of the image ((0, 0) its top-left corner):
    // where a mark anchored in the patient lies on this frame.
    std::optional<std::array<double, 12>> projection;
    // Version 4: a slice frame (a grey PNG still; `seq` counts the view's slices
    // messages) says its view and plane; none for a frame of the 3D view.
    std::optional<SliceFrameInfo> slice;
    bool operator==(const FrameHeader&) const = default;
};

std::string frameMessage(const FrameHeader& header, std::string_view imageBytes);

// The inverse of frameMessage (for clients and tests). Throws ProtocolError
// ("malformed", fatal) when the layout or the header is wrong.
struct ParsedFrame {
    FrameHeader header;
    std::string_view image; // points into the message
};
ParsedFrame parseFrameMessage(std::string_view message);

} // namespace lucent::remote
