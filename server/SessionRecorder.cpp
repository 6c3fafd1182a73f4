#include "server/SessionRecorder.h"

#include <QDateTime>

#include <algorithm>

#include "server/RecordingStore.h"

namespace lucent::remote {

SessionRecorder::SessionRecorder(std::filesystem::path storeDir, std::string series,
                                 const RenderDescription& start, const ViewStream* view)
    : storeDir_(std::move(storeDir)), id_(newRecordingId()), view_(view) {
    header_.series = std::move(series);
    header_.width = std::clamp(start.width, kMinImageSide, kMaxImageSide);
    header_.height = std::clamp(start.height, kMinImageSide, kMaxImageSide);
    header_.createdMs = QDateTime::currentMSecsSinceEpoch();
    for (const ClientMessage& m : viewMessages(start)) {
        lines_.push_back(recordingStartLine(m));
        bytes_ += lines_.back().size() + 1;
    }
    clock_.start();
}

bool SessionRecorder::add(const ClientMessage& message) {
    if (!isRecordedMessage(message)) {
        return true;
    }
    const std::int64_t atMs = clock_.elapsed();
    std::string line = recordedMessageLine(atMs, message);
    // The header is written last; 256 bytes hold it.
    if (atMs > kMaxRecordingMs || messages_ + 1 > kMaxRecordedMessages ||
        bytes_ + line.size() + 1 + 256 > kMaxRecordingBytes) {
        return false;
    }
    bytes_ += line.size() + 1;
    lines_.push_back(std::move(line));
    ++messages_;
    header_.durationMs = atMs;
    header_.views += showsRecordedView(message) ? 1 : 0;
    return true;
}

RecordingStopped SessionRecorder::finish(const std::string& reason) {
    header_.durationMs =
        std::min(std::max<std::int64_t>(header_.durationMs, clock_.elapsed()), kMaxRecordingMs);
    std::string text = recordingHeaderLine(header_) + "\n";
    text.reserve(bytes_ + text.size());
    for (const std::string& line : lines_) {
        text += line;
        text += '\n';
    }
    storeRecording(storeDir_, id_, text);
    return {id_, header_.views, header_.durationMs, reason};
}

} // namespace lucent::remote
