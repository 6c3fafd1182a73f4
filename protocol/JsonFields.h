#pragma once
// The checks every reader of a client message makes on its fields: no unknown
// key, and strings that must be there. One home for the readers of
// ClientMessageJson, MarkMessageJson and RecordingMessageJson. Private to
// protocol/ (.cpp files only).

#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "protocol/ProtocolError.h"

namespace lucent::remote {

// Every key of `object` must be one of `known` ("type" always is); else a
// bad-request naming the message and the key.
inline void checkKeys(const nlohmann::json& object, const std::string& type,
                      const std::set<std::string>& known) {
    for (const auto& [key, value] : object.items()) {
        if (key != "type" && !known.count(key)) {
            throwBadRequest(type + ": unknown field '" + key + "'");
        }
    }
}

// The non-empty string `key` of `object`; else a bad-request naming it.
inline std::string requiredString(const nlohmann::json& object, const char* key,
                                  const std::string& type) {
    const auto it = object.find(key);
    if (it == object.end() || !it->is_string() || it->get<std::string>().empty()) {
        throwBadRequest(type + ": '" + key + "' must be a non-empty string");
    }
    return it->get<std::string>();
}

} // namespace lucent::remote
