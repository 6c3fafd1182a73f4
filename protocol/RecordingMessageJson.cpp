#include "protocol/RecordingMessageJson_p.h"

#include <set>

#include "protocol/JsonFields.h"
#include "protocol/ProtocolError.h"

namespace lucent::remote {
namespace {

using Json = nlohmann::json;

RecordRequest parseRecord(const Json& m) {
    checkKeys(m, "record", {"state"});
    const std::string state = requiredString(m, "state", "record");
    if (state != "start" && state != "stop") {
        throwBadRequest("record: 'state' must be start or stop");
    }
    return {state == "start"};
}

// The id names a file in the store: letters, digits, '-' and '_' only.
ReplayRequest parseReplay(const Json& m) {
    checkKeys(m, "replay", {"recording", "pace"});
    ReplayRequest r{requiredString(m, "recording", "replay"), ReplayPace::Original};
    if (r.recording.size() > kMaxRecordingIdBytes ||
        r.recording.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                      "0123456789-_") != std::string::npos) {
        throwBadRequest("replay: 'recording' must be a recording's id (at most " +
                        std::to_string(kMaxRecordingIdBytes) + " letters, digits, '-' and '_')");
    }
    if (m.contains("pace")) {
        const std::string pace = requiredString(m, "pace", "replay");
        if (pace != "original" && pace != "step") {
            throwBadRequest("replay: 'pace' must be original or step");
        }
        r.pace = pace == "step" ? ReplayPace::Step : ReplayPace::Original;
    }
    return r;
}

} // namespace

std::optional<ClientMessage> parseRecordingMessage(const Json& m, const std::string& type) {
    if (type == "record") {
        return parseRecord(m);
    }
    if (type == "replay") {
        return parseReplay(m);
    }
    if (type == "recording-list" || type == "replay-step" || type == "replay-stop") {
        checkKeys(m, type, {});
        if (type == "recording-list") {
            return RecordingListRequest{};
        }
        return type == "replay-step" ? ClientMessage(ReplayStep{}) : ClientMessage(ReplayStop{});
    }
    return std::nullopt;
}

} // namespace lucent::remote
