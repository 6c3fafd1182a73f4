#include "protocol/Recording.h"

#include <fstream>
#include <iterator>
#include <set>

#include <nlohmann/json.hpp>

#include "protocol/ClientMessageJson.h"
#include "protocol/ViewMessages.h"

namespace lucent::remote {
namespace {

using Json = nlohmann::json;

// Where a line of a recording is, for its errors.
struct Place {
    const std::string& name;
    std::size_t line = 0;
    [[noreturn]] void fail(const std::string& what) const {
        throw RecordingError(name + ":" + std::to_string(line) + ": " + what);
    }
};

void checkKeys(const Json& object, const std::set<std::string>& known, const Place& at) {
    for (const auto& [key, value] : object.items()) {
        if (!known.count(key)) {
            at.fail("unknown field '" + key + "'");
        }
    }
}

std::int64_t integer(const Json& object, const char* key, std::int64_t lo, std::int64_t hi,
                     const Place& at) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_number_integer() || it->get<std::int64_t>() < lo ||
        it->get<std::int64_t>() > hi) {
        at.fail(std::string("'") + key + "' must be an integer from " + std::to_string(lo) +
                " to " + std::to_string(hi));
    }
    return it->get<std::int64_t>();
}

Json objectLine(std::string_view text, const Place& at) {
    Json line = Json::parse(text, nullptr, false);
    if (line.is_discarded() || !line.is_object()) {
        at.fail("not a JSON object");
    }
    return line;
}

RecordingHeader parseHeader(const Json& h, const Place& at) {
    checkKeys(h,
              {"lucent_recording", "series", "width", "height", "created", "duration_ms", "views"},
              at);
    RecordingHeader header;
    if (!h.contains("lucent_recording")) {
        at.fail("not a Lucent recording (no 'lucent_recording' in the first line)");
    }
    header.format = int(integer(h, "lucent_recording", 1, 1000, at));
    if (header.format != kRecordingFormat) {
        at.fail("recording format " + std::to_string(header.format) + " (this build reads " +
                std::to_string(kRecordingFormat) + ")");
    }
    const auto series = h.find("series");
    if (series == h.end() || !series->is_string() || series->get<std::string>().empty()) {
        at.fail("'series' must be a non-empty string");
    }
    header.series = series->get<std::string>();
    header.width = int(integer(h, "width", kMinImageSide, kMaxImageSide, at));
    header.height = int(integer(h, "height", kMinImageSide, kMaxImageSide, at));
    header.createdMs = integer(h, "created", 0, INT64_MAX, at);
    header.durationMs = integer(h, "duration_ms", 0, kMaxRecordingMs, at);
    header.views = int(integer(h, "views", 1, std::int64_t(kMaxRecordedMessages) + 1, at));
    return header;
}

// The message a line holds, as the protocol's reader reads it off the wire.
ClientMessage lineMessage(const Json& value, const Place& at) {
    if (!value.is_object()) {
        at.fail("the message must be a JSON object");
    }
    try {
        return parseClientMessage(value.dump(), kProtocolVersion);
    } catch (const ProtocolError& e) {
        at.fail(e.what());
    }
}

} // namespace

bool isRecordedMessage(const ClientMessage& message) {
    return std::holds_alternative<CameraUpdate>(message) ||
           std::holds_alternative<TransferFunctionUpdate>(message) ||
           std::holds_alternative<ModeUpdate>(message) ||
           std::holds_alternative<ClipUpdate>(message) ||
           std::holds_alternative<SamplingUpdate>(message) ||
           std::holds_alternative<SizeUpdate>(message) ||
           std::holds_alternative<InteractionUpdate>(message) ||
           std::holds_alternative<PointerUpdate>(message) ||
           std::holds_alternative<MarkPlace>(message) ||
           std::holds_alternative<MarksClear>(message);
}

bool showsRecordedView(const ClientMessage& message) {
    return isRecordedMessage(message) && isViewMessage(message) &&
           !std::holds_alternative<InteractionUpdate>(message);
}

bool isRecordingControl(const ClientMessage& message) {
    return std::holds_alternative<RecordRequest>(message) ||
           std::holds_alternative<RecordingListRequest>(message) ||
           std::holds_alternative<ReplayRequest>(message) ||
           std::holds_alternative<ReplayStep>(message) ||
           std::holds_alternative<ReplayStop>(message);
}

std::string recordingHeaderLine(const RecordingHeader& h) {
    return Json{{"lucent_recording", h.format},
                {"series", h.series},
                {"width", h.width},
                {"height", h.height},
                {"created", h.createdMs},
                {"duration_ms", h.durationMs},
                {"views", h.views}}
        .dump();
}

std::string recordingStartLine(const ClientMessage& message) {
    return R"({"start":)" + writeClientMessage(message) + "}";
}

std::string recordedMessageLine(std::int64_t atMs, const ClientMessage& message) {
    return R"({"at_ms":)" + std::to_string(atMs) + R"(,"message":)" + writeClientMessage(message) +
           "}";
}

Recording parseRecording(std::string_view text, const std::string& name) {
    Place at{name, 0};
    if (text.size() > kMaxRecordingBytes) {
        at.fail("larger than a recording may be (" + std::to_string(kMaxRecordingBytes) +
                " bytes)");
    }
    Recording recording;
    int views = 1;
    std::size_t begin = 0;
    while (begin < text.size()) {
        const std::size_t end = std::min(text.find('\n', begin), text.size());
        const std::string_view row = text.substr(begin, end - begin);
        begin = end + 1;
        ++at.line;
        if (row.empty()) {
            at.fail("an empty line");
        }
        const Json line = objectLine(row, at);
        if (at.line == 1) {
            recording.header = parseHeader(line, at);
        } else if (line.contains("start")) {
            checkKeys(line, {"start"}, at);
            if (!recording.messages.empty()) {
                at.fail("a start line after the recorded messages");
            }
            ClientMessage m = lineMessage(line["start"], at);
            if (!showsRecordedView(m)) {
                at.fail("'" + std::string(messageType(m)) + "' does not make the start view");
            }
            recording.start.push_back(std::move(m));
        } else {
            checkKeys(line, {"at_ms", "message"}, at);
            const std::int64_t atMs = integer(line, "at_ms", 0, recording.header.durationMs, at);
            if (!recording.messages.empty() && atMs < recording.messages.back().atMs) {
                at.fail("'at_ms' goes back in time");
            }
            if (!line.contains("message")) {
                at.fail("no 'message'");
            }
            ClientMessage m = lineMessage(line["message"], at);
            if (!isRecordedMessage(m)) {
                at.fail("'" + std::string(messageType(m)) + "' is not a message recordings keep");
            }
            if (recording.messages.size() >= kMaxRecordedMessages) {
                at.fail("more than " + std::to_string(kMaxRecordedMessages) + " messages");
            }
            views += showsRecordedView(m) ? 1 : 0;
            recording.messages.push_back({atMs, std::move(m)});
        }
    }
    if (at.line == 0) {
        at.fail("empty: not a recording");
    }
    if (recording.start.empty()) {
        at.fail("no start view (the lines {\"start\":...} after the header)");
    }
    if (views != recording.header.views) {
        at.fail("the header counts " + std::to_string(recording.header.views) +
                " views, the lines hold " + std::to_string(views) + " (cut short?)");
    }
    return recording;
}

Recording readRecording(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        throw RecordingError(file.string() + ": cannot read the recording");
    }
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    return parseRecording(text, file.string());
}

RecordingHeader readRecordingHeader(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::string first;
    if (!in || !std::getline(in, first)) {
        throw RecordingError(file.string() + ": cannot read the recording");
    }
    const std::string name = file.string();
    const Place at{name, 1};
    return parseHeader(objectLine(first, at), at);
}

RenderDescription recordedStart(const Recording& recording) {
    RenderDescription d;
    for (const ClientMessage& m : recording.start) {
        if (const auto error = applyViewMessage(m, d)) {
            throw RecordingError("the start view: " + *error);
        }
    }
    return d;
}

RenderDescription recordedViewAfter(const Recording& recording, std::size_t end) {
    RenderDescription d = recordedStart(recording);
    for (std::size_t n = 0; n < end && n < recording.messages.size(); ++n) {
        if (const auto error = applyViewMessage(recording.messages[n].message, d)) {
            throw RecordingError("recorded message " + std::to_string(n + 1) + ": " + *error);
        }
    }
    return d;
}

RenderDescription recordedViewAt(const Recording& recording, std::int64_t ms) {
    std::size_t end = 0;
    while (end < recording.messages.size() && recording.messages[end].atMs <= ms) {
        ++end;
    }
    return recordedViewAfter(recording, end);
}

std::vector<RenderDescription> recordedViews(const Recording& recording) {
    RenderDescription d = recordedStart(recording);
    std::vector<RenderDescription> views{d};
    for (std::size_t n = 0; n < recording.messages.size(); ++n) {
        const ClientMessage& m = recording.messages[n].message;
        if (const auto error = applyViewMessage(m, d)) {
            throw RecordingError("recorded message " + std::to_string(n + 1) + ": " + *error);
        }
        if (showsRecordedView(m)) {
            views.push_back(d);
        }
    }
    return views;
}

} // namespace lucent::remote
