#pragma once
// The invites to teaching sessions (docs/protocol.md, "Invites"): codes of 192
// random bits (the system's CSPRNG) that let their holder only follow one
// session. The book keeps a code's SHA-256, never the code, and compares
// digests in constant time; a code lives until it expires, is revoked or its
// session ends. Nothing here is logged.

#include <QString>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lucent::remote {

class InviteBook {
public:
    // Invites a session may issue over its life (revoked and expired ones count).
    static constexpr int kMaxPerSession = 64;

    struct Issued {
        std::uint64_t number = 0; // names it to its presenter (invite-revoke); not secret
        std::string code;         // the secret: 32 characters of base64url
        std::int64_t expires = 0; // seconds since the epoch
    };
    // An invite to `session` until now + lifetimeSeconds; nullopt once the session
    // has issued kMaxPerSession.
    std::optional<Issued> issue(const QString& session, std::int64_t lifetimeSeconds);

    enum class State { Valid, Unknown, Expired, Revoked, SessionEnded };
    struct Found {
        State state = State::Unknown;
        QString session;
        std::uint64_t number = 0;
    };
    Found find(std::string_view code) const;
    // Why an invite in this state is refused ("the invite has expired").
    static std::string refusal(State state);

    // False when the session has no invite of this number.
    bool revoke(const QString& session, std::uint64_t number);
    // Its invites are refused from now on ("the session has ended"); their
    // records go a day after they expired.
    void sessionEnded(const QString& session);

private:
    struct Record {
        std::string digest; // SHA-256 of the code
        QString session;
        std::uint64_t number = 0;
        std::int64_t expires = 0;
        bool revoked = false;
        bool sessionEnded = false;
    };
    void forgetOld();

    std::vector<Record> records_;
    std::uint64_t nextNumber_ = 1;
};

} // namespace lucent::remote
