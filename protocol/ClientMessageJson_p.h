#pragma once
// The readers behind parseClientMessage (and the options' writer), by concern:
// the messages of the options table (camera, mode, sampling:
// OptionMessageJson.cpp), the other view messages (ViewMessageJson.cpp), and
// authentication, invites and teaching sessions (SessionMessageJson.cpp). Each
// reader throws ProtocolError "bad-request" naming the message and the key.
// Private to protocol/.

#include <string>

#include <nlohmann/json.hpp>

#include "protocol/ClientMessages.h"

namespace lucent::remote {

// camera, mode, sampling: the keys of the options table's rows for `type`.
OptionUpdate parseOptions(const nlohmann::json& m, const std::string& type);
void writeOptions(nlohmann::json& m, const OptionUpdate& update);

// tf, clip, quality, size, interaction.
TransferFunctionUpdate parseTransferFunctionUpdate(const nlohmann::json& m);
ClipUpdate parseClip(const nlohmann::json& m);
QualityUpdate parseQuality(const nlohmann::json& m);
SizeUpdate parseSize(const nlohmann::json& m);
InteractionUpdate parseInteraction(const nlohmann::json& m);

// auth (as a connection of `version` reads it), invite-create, invite-revoke,
// free-look, session-join, session-handover.
AuthRequest parseAuth(const nlohmann::json& m, int version);
InviteCreate parseInviteCreate(const nlohmann::json& m);
InviteRevoke parseInviteRevoke(const nlohmann::json& m);
FreeLook parseFreeLook(const nlohmann::json& m);
SessionJoin parseSessionJoin(const nlohmann::json& m);
SessionHandover parseSessionHandover(const nlohmann::json& m);

} // namespace lucent::remote
