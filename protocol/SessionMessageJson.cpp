// Authentication, invites and teaching sessions: auth, invite-create,
// invite-revoke, free-look, session-join, session-handover.
#include <string_view>

#include <nlohmann/json.hpp>

#include "protocol/ClientMessageJson_p.h"
#include "protocol/JsonFields.h"

namespace lucent::remote {
namespace {

using Json = nlohmann::json;

// "http(s)://host[:port]": letters, digits and . - : [ ] after the scheme.
bool isOrigin(std::string_view origin) {
    for (const std::string_view scheme : {"https://", "http://"}) {
        if (origin.starts_with(scheme)) {
            const std::string_view rest = origin.substr(scheme.size());
            return !rest.empty() && rest.size() <= 253 + 6 &&
                   rest.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                          "0123456789.-:[]") == std::string_view::npos;
        }
    }
    return false;
}

} // namespace

AuthRequest parseAuth(const Json& m, int version) {
    if (version < 3 && m.contains("invite")) {
        // Before version 3 an unknown field; an invite holder learns what it needs.
        throw ProtocolError("auth-failed",
                            "an invite needs protocol version 3 (offer the subprotocol lucent.v3); "
                            "this connection speaks version " +
                                std::to_string(version),
                            true);
    }
    if (version < 3) {
        checkKeys(m, "auth", {"token"});
        return {requiredString(m, "token", "auth"), {}};
    }
    checkKeys(m, "auth", {"token", "invite"});
    if (m.contains("token") == m.contains("invite")) {
        throwBadRequest("auth: give exactly one of 'token' and 'invite'");
    }
    if (m.contains("token")) {
        return {requiredString(m, "token", "auth"), {}};
    }
    std::string invite = requiredString(m, "invite", "auth");
    if (invite.size() > kMaxInviteCodeBytes) {
        throwBadRequest("auth: 'invite' is longer than " + std::to_string(kMaxInviteCodeBytes) +
                        " characters");
    }
    return {{}, std::move(invite)};
}

InviteCreate parseInviteCreate(const Json& m) {
    checkKeys(m, "invite-create", {"lifetime", "origin"});
    InviteCreate c;
    if (const auto it = m.find("lifetime"); it != m.end()) {
        if (!it->is_number_integer() || it->get<long long>() < 1 ||
            it->get<long long>() > kMaxInviteLifetimeSeconds) {
            throwBadRequest("invite-create: 'lifetime' must be an integer number of seconds from "
                            "1 to " +
                            std::to_string(kMaxInviteLifetimeSeconds));
        }
        c.lifetimeSeconds = it->get<std::int64_t>();
    }
    if (m.contains("origin")) {
        c.origin = requiredString(m, "origin", "invite-create");
        if (!isOrigin(*c.origin)) {
            throwBadRequest("invite-create: 'origin' must be http(s)://HOST[:PORT], without a "
                            "path");
        }
    }
    return c;
}

InviteRevoke parseInviteRevoke(const Json& m) {
    checkKeys(m, "invite-revoke", {"invite"});
    const auto it = m.find("invite");
    if (it == m.end() || !it->is_number_unsigned() || it->get<std::uint64_t>() == 0) {
        throwBadRequest("invite-revoke: 'invite' must be the number invite-created gave");
    }
    return {it->get<std::uint64_t>()};
}

FreeLook parseFreeLook(const Json& m) {
    checkKeys(m, "free-look", {"state"});
    const std::string state = requiredString(m, "state", "free-look");
    if (state != "start" && state != "end") {
        throwBadRequest("free-look: 'state' must be start or end");
    }
    return {state == "start"};
}

SessionJoin parseSessionJoin(const Json& m) {
    checkKeys(m, "session-join", {"session"});
    std::string id = requiredString(m, "session", "session-join");
    if (id.size() > 64) {
        throwBadRequest("session-join: 'session' is longer than 64 characters");
    }
    return {std::move(id)};
}

SessionHandover parseSessionHandover(const Json& m) {
    checkKeys(m, "session-handover", {"to"});
    const auto it = m.find("to");
    if (it == m.end() || !it->is_number_unsigned() || it->get<std::uint64_t>() == 0) {
        throwBadRequest("session-handover: 'to' must be a member number from session-state");
    }
    return {it->get<std::uint64_t>()};
}
} // namespace lucent::remote
