#pragma once
// How the workstation joins a running teaching session as a follower
// (docs/protocol.md, "Invites" and "Teaching sessions"): by an invite's join
// link (`https://HOST:PORT/#invite=CODE`, the code then rides in the
// `lucent.invite.<CODE>` subprotocol), or by a token of the server and the
// session's id (`session-join`).

#include <optional>

#include <QString>
#include <QUrl>

namespace lucent {

struct SessionFollow {
    QUrl url;        // ws://HOST:PORT/ or wss://HOST:PORT/
    QString invite;  // an invite's code; or, when empty:
    QString token;   // one of the server's --token-file lines
    QString session; // and the id of its session

    // A join link as the server's invite-created gives it (http -> ws,
    // https -> wss; a ws:// or wss:// link is taken as it is). None when it is
    // not one, with `why` naming what is wrong.
    static std::optional<SessionFollow> fromLink(const QString& link, QString* why);

    // Empty when usable, else what is wrong, naming the field.
    QString problem() const;
    bool byInvite() const { return !invite.isEmpty(); }
    bool operator==(const SessionFollow&) const = default;
};

} // namespace lucent
