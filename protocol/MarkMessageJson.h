#pragma once
// The JSON of the pointer and mark messages (MarkMessages.h): the readers refuse
// what docs/protocol.md refuses, with a bad-request that names the message and
// the key. Used by ClientMessageJson.cpp and ServerMessages.cpp.

#include <nlohmann/json.hpp>

#include "protocol/MarkMessages.h"

namespace lucent::remote {

// Client messages (the `type` already read; unknown keys refused).
PointerUpdate parsePointerUpdate(const nlohmann::json& m);
MarkPlace parseMarkPlace(const nlohmann::json& m);
// Their fields, added to `m` (which holds the type).
void writePointerUpdate(nlohmann::json& m, const PointerUpdate& p);
void writeMarkPlace(nlohmann::json& m, const MarkPlace& p);

// Server messages: the whole message, and its reader (malformed: nlohmann's
// exceptions or ProtocolError).
nlohmann::json pointerShownJson(const PointerShown& p);
nlohmann::json markShownJson(const MarkShown& m);
PointerShown readPointerShown(const nlohmann::json& m);
MarkShown readMarkShown(const nlohmann::json& m);

} // namespace lucent::remote
