#pragma once
// Protocol versions (docs/protocol.md, "Versions"). A client offers the versions
// it speaks in the WebSocket handshake, newest first, as subprotocols lucent.v<N>;
// the server selects the first it speaks and says the connection's version in
// `hello` (a client that offers none it speaks is served version 1). A message
// newer than the connection's version is an unknown type to the server (fatal),
// and a client does not send it to a server whose `hello` names an older version.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lucent::remote {

// The newest version this build speaks, and the oldest it still speaks.
inline constexpr int kProtocolVersion = 4;
inline constexpr int kOldestProtocolVersion = 1;

// "lucent.v2".
std::string subprotocolName(int version);
// 2 for "lucent.v2": the version a name stands for when this build speaks it;
// nullopt for other names and versions.
std::optional<int> subprotocolVersion(std::string_view name);
// The names of every version this build speaks, newest first (what a server supports).
std::vector<std::string> supportedSubprotocols();

} // namespace lucent::remote
