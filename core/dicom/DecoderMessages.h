#pragma once
// The messages between Lucent and lucent-frame-decoder, over a local stream socket
// (its standard input and output): one request, one reply, in turn. Both ends are
// the same build on the same machine, so integers go in native byte order.
// Private to lucent_io and the decoder.

#include <cstdint>
#include <optional>
#include <string>
#include <variant>

#include "core/dicom/FrameDecoder.h"

namespace lucent {

struct DecodeRequest {
    std::string file;
    PixelLayout layout;
    int frames = 1;
};

// What the decoder made of a request: the frames, or why not.
using DecodeReply = std::variant<DecodedFrames, std::string>;

// Whole messages or nothing: false when the other end is gone or the bytes are not
// a message (a request's sizes out of range). Retries interrupted calls; never
// raises SIGPIPE.
bool writeRequest(int fd, const DecodeRequest& request);
std::optional<DecodeRequest> readRequest(int fd);
bool writeReply(int fd, const DecodeReply& reply);
// `maxBytes` bounds the decoded buffer the reader accepts.
std::optional<DecodeReply> readReply(int fd, std::size_t maxBytes);

} // namespace lucent
