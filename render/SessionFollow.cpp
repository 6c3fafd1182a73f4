#include "render/SessionFollow.h"

#include <algorithm>

#include <QMap>
#include <QObject>
#include <QUrlQuery>

namespace lucent {

namespace {

// Invite codes are base64url (32 characters); the server takes at most 128.
constexpr int kMaxInviteLength = 128;
constexpr int kMaxSessionLength = 64;

bool isCodeCharacter(QChar c) {
    const char16_t u = c.unicode();
    return (u >= u'a' && u <= u'z') || (u >= u'A' && u <= u'Z') || (u >= u'0' && u <= u'9') ||
           u == u'-' || u == u'_';
}

} // namespace

std::optional<SessionFollow> SessionFollow::fromLink(const QString& link, QString* why) {
    const auto refuse = [why](const QString& reason) {
        if (why) {
            *why = reason;
        }
        return std::nullopt;
    };
    const QUrl url(link.trimmed(), QUrl::StrictMode);
    if (link.trimmed().isEmpty()) {
        return refuse(
            QObject::tr("join link: empty (e.g. https://lecture-host:8443/#invite=CODE)"));
    }
    if (!url.isValid()) {
        return refuse(QObject::tr("join link: %1").arg(url.errorString()));
    }
    static const QMap<QString, QString> kSocketScheme{
        {"http", "ws"}, {"https", "wss"}, {"ws", "ws"}, {"wss", "wss"}};
    if (!kSocketScheme.contains(url.scheme())) {
        return refuse(
            QObject::tr("join link: must start with https:// or http://, not %1")
                .arg(url.scheme().isEmpty() ? QObject::tr("no scheme") : url.scheme() + "://"));
    }
    if (url.host().isEmpty()) {
        return refuse(QObject::tr("join link: no host"));
    }
    const QUrlQuery fragment(url.fragment(QUrl::FullyEncoded));
    if (!fragment.hasQueryItem("invite")) {
        return refuse(QObject::tr("join link: no invite (it ends with #invite=CODE)"));
    }
    SessionFollow follow;
    follow.invite = fragment.queryItemValue("invite", QUrl::FullyDecoded);
    if (follow.invite.isEmpty()) {
        return refuse(QObject::tr("join link: the invite code after #invite= is empty"));
    }
    QUrl server;
    server.setScheme(kSocketScheme.value(url.scheme()));
    server.setHost(url.host());
    server.setPort(url.port());
    server.setPath("/");
    follow.url = server;
    if (const QString problem = follow.problem(); !problem.isEmpty()) {
        return refuse(problem);
    }
    return follow;
}

QString SessionFollow::problem() const {
    if (url.isEmpty() || !url.isValid() || (url.scheme() != "ws" && url.scheme() != "wss") ||
        url.host().isEmpty()) {
        return QObject::tr("server URL: must be ws://HOST:PORT/ or wss://HOST:PORT/");
    }
    if (!url.userInfo().isEmpty() || url.hasQuery()) {
        return QObject::tr("server URL: no query or user part (the token goes in its own field)");
    }
    if (!invite.isEmpty()) {
        if (invite.size() > kMaxInviteLength ||
            !std::all_of(invite.begin(), invite.end(), isCodeCharacter)) {
            return QObject::tr("invite: not an invite code (letters, digits, - and _; at most %1)")
                .arg(kMaxInviteLength);
        }
        return {};
    }
    if (token.trimmed().isEmpty()) {
        return QObject::tr("token: empty (a follower without an invite needs one of the "
                           "server's --token-file lines)");
    }
    if (session.trimmed().isEmpty() || session.size() > kMaxSessionLength) {
        return QObject::tr("session: the id the presenter's session-created gave (at most %1 "
                           "characters)")
            .arg(kMaxSessionLength);
    }
    return {};
}

} // namespace lucent
