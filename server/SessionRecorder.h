#pragma once
// A recording being made: the view when it began and every recorded message
// (protocol/Recording.h, isRecordedMessage) its view accepted after, with its
// time. It lives in memory, within the limits of Recording.h, and reaches the
// store whole when it stops (RecordingStore.h): a recording is never half-written.

#include <QElapsedTimer>
#include <QObject>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/scene/RenderDescription.h"
#include "protocol/ProtocolMessages.h"

namespace lucent::remote {

class ViewStream;

class SessionRecorder : public QObject {
public:
    // Records `view` (which shows `series`, the id the server lists) from now,
    // starting from `start`, what the view shows.
    SessionRecorder(std::filesystem::path storeDir, std::string series,
                    const RenderDescription& start, const ViewStream* view);

    const std::string& id() const { return id_; }
    const ViewStream* view() const { return view_; }
    // Keeps a message the view accepted when isRecordedMessage(); false when
    // it would pass a limit (it is not kept: the recording should stop).
    bool add(const ClientMessage& message);
    // Writes it into the store. Throws std::runtime_error naming the file.
    RecordingStopped finish(const std::string& reason);

private:
    std::filesystem::path storeDir_;
    std::string id_;
    RecordingHeader header_;
    const ViewStream* view_; // compared, never used: the view may be gone
    QElapsedTimer clock_;
    std::vector<std::string> lines_; // the start view and the recorded messages
    std::size_t bytes_ = 0;
    std::size_t messages_ = 0;
};

} // namespace lucent::remote
