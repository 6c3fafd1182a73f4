#pragma once
// The one reader and the one writer of the client's JSON messages.

#include <string>
#include <string_view>

#include "protocol/ClientMessages.h"
#include "protocol/ProtocolError.h"

namespace lucent::remote {

// Parses one text message of a connection that speaks `version`. Throws
// ProtocolError: "too-large", "malformed" and "unknown-type" (a type that
// `version` does not have) are fatal; "bad-request" (a field missing, unknown, of
// the wrong type or out of range; the message names it) is not.
ClientMessage parseClientMessage(std::string_view text, int version = kProtocolVersion);

// The message as compact JSON. Writes what it is given: parseClientMessage checks.
std::string writeClientMessage(const ClientMessage& message);

} // namespace lucent::remote
