#pragma once
// The readers of the recording and replay messages (version 4: record,
// recording-list, replay, replay-step, replay-stop) for parseClientMessage.
// Private to protocol/.

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "protocol/ClientMessages.h"

namespace lucent::remote {

// The message when `type` is one of these (throws ProtocolError "bad-request"
// naming the message and the key, as every reader does); nullopt for other types.
std::optional<ClientMessage> parseRecordingMessage(const nlohmann::json& m,
                                                   const std::string& type);

} // namespace lucent::remote
