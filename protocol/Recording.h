#pragma once
// A recorded teaching session (docs/protocol.md, "Recording and replay"): not
// video, the protocol's own messages with their times. One JSON object a line:
//
//   {"lucent_recording":1,"series":UID,"width":W,"height":H,"created":MS,
//    "duration_ms":D,"views":N}                      the header
//   {"start":MESSAGE}                                 the view when recording began
//   {"at_ms":T,"message":MESSAGE}                     each recorded message, in order
//
// MESSAGE is what writeClientMessage writes, read back by parseClientMessage:
// one writer and one reader for the wire and the file. The server writes them
// (server/SessionRecorder), its replay and lucent-cli movie --replay read them.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene/RenderDescription.h"
#include "protocol/ClientMessages.h"

namespace lucent::remote {

inline constexpr int kRecordingFormat = 1;
// A recording stops by itself at the first of these.
inline constexpr std::int64_t kMaxRecordingMs = 2 * 60 * 60 * 1000;
inline constexpr std::size_t kMaxRecordedMessages = 250000;
inline constexpr std::size_t kMaxRecordingBytes = std::size_t(32) << 20;

// A file that is not a whole recording: the message names the file and line.
class RecordingError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The messages a recording keeps (those that change what the view shows, and
// the interaction around drags). The one list: pointer and marks join it here.
bool isRecordedMessage(const ClientMessage& message);
// A recorded message after which the view shows a new picture: one step of a
// stepped replay, one of a recording's `views`.
bool showsRecordedView(const ClientMessage& message);
// record, recording-list, replay, replay-step, replay-stop.
bool isRecordingControl(const ClientMessage& message);

struct RecordingHeader {
    int format = kRecordingFormat;
    std::string series; // the original series' id as the server lists it
    int width = 0, height = 0;
    std::int64_t createdMs = 0; // since 1970-01-01 UTC
    std::int64_t durationMs = 0;
    int views = 1;
};

struct RecordedMessage {
    std::int64_t atMs = 0; // since the recording began
    ClientMessage message;
};

struct Recording {
    RecordingHeader header;
    std::vector<ClientMessage> start; // view messages: the view when recording began
    std::vector<RecordedMessage> messages;
};

// The lines of the file, each without its newline.
std::string recordingHeaderLine(const RecordingHeader& header);
std::string recordingStartLine(const ClientMessage& message);
std::string recordedMessageLine(std::int64_t atMs, const ClientMessage& message);

// Reads a whole recording; `name` names it in errors. Throws RecordingError
// ("NAME:LINE: what"): not JSON, a missing or unknown field, a message the
// protocol refuses or a recording does not keep, times out of order, counts
// that disagree with the header, over the limits.
Recording parseRecording(std::string_view text, const std::string& name);
Recording readRecording(const std::filesystem::path& file);
// The header alone (the first line), for lists.
RecordingHeader readRecordingHeader(const std::filesystem::path& file);

// The view at the start: the start messages applied to a fresh description
// (the server's view after `open`, at the recorded size). Throws
// RecordingError when a message cannot apply (a preset this build lacks).
RenderDescription recordedStart(const Recording& recording);
// The view after the recorded messages before index `end` (from recordedStart).
RenderDescription recordedViewAfter(const Recording& recording, std::size_t end);
// The view current `ms` after the recording began.
RenderDescription recordedViewAt(const Recording& recording, std::int64_t ms);
// Each recorded view in turn: the start, then the view after each message that
// showsRecordedView (header.views of them).
std::vector<RenderDescription> recordedViews(const Recording& recording);

} // namespace lucent::remote
