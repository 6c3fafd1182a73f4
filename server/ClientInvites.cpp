// ClientConnection: invites to teaching sessions. A token's holder presents and
// may invite; an invite's holder is authenticated into its session as a
// follower and may do nothing but follow (and leave). Invite codes are never
// logged.
#include <QLoggingCategory>

#include <algorithm>
#include <cctype>

#include "server/ClientConnection.h"
#include "server/InviteBook.h"
#include "server/RenderServer.h"
#include "server/TeachingSession.h"

namespace lucent::remote {
namespace {

Q_LOGGING_CATEGORY(lcInvite, "lucent.server.invite")

constexpr int kInviteVersion = 3;

// Letters, digits and . - : [ ]: what a Host header of a name or an address holds.
bool isHostAndPort(const QByteArray& host) {
    return !host.isEmpty() && host.size() <= 259 &&
           std::all_of(host.begin(), host.end(), [](char c) {
               return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ||
                      c == ':' || c == '[' || c == ']';
           });
}

} // namespace

void ClientConnection::authenticateInvite(const std::string& code) {
    if (version_ < kInviteVersion) {
        sendError("auth-failed",
                  "an invite needs protocol version 3 (offer the subprotocol lucent.v3); this "
                  "connection speaks version " +
                      std::to_string(version_),
                  true);
        return;
    }
    const InviteBook::Found found = server_.invites().find(code);
    TeachingSession* session =
        found.state == InviteBook::State::Valid ? server_.findSession(found.session) : nullptr;
    if (found.state != InviteBook::State::Valid || !session) {
        const auto state = session || found.state != InviteBook::State::Valid
                               ? found.state
                               : InviteBook::State::SessionEnded;
        sendError("auth-failed", InviteBook::refusal(state), true);
        return;
    }
    if (session->full()) {
        sendError("session-full", "the session has no room for another member", true);
        return;
    }
    authenticated_ = true;
    invite_ = found.number;
    authTimer_.stop();
    qCInfo(lcInvite) << "client" << id_ << "authenticated by invite" << invite_
                     << ", protocol version" << version_;
    sendJson(writeServerMessage(helloFor(version_, server_.backendDescription().toStdString())));
    joinSession(*session);
}

bool ClientConnection::refusedToInvitee(const ClientMessage& message) {
    if (invite_ == 0 || isViewMessage(message) || std::holds_alternative<SlicesRequest>(message) ||
        std::holds_alternative<SessionLeave>(message) ||
        std::holds_alternative<FreeLook>(message)) {
        return false; // view messages: not-presenter, as for any follower; free look is following
    }
    sendError("forbidden",
              std::string(messageType(message)) +
                  ": an invite lets this client only follow its session",
              false);
    return true;
}

void ClientConnection::handleInvite(const ClientMessage& message) {
    if (!session_) {
        sendError("out-of-order", "not in a session", true);
        return;
    }
    if (!session_->isPresenter(*this)) {
        sendError("not-presenter", "only the presenter of the session invites", false);
        return;
    }
    InviteBook& invites = server_.invites();
    if (const auto* revoke = std::get_if<InviteRevoke>(&message)) {
        if (!invites.revoke(session_->id(), revoke->invite)) {
            sendError("not-found",
                      "invite-revoke: no invite " + std::to_string(revoke->invite) +
                          " in this session",
                      false);
            return;
        }
        qCInfo(lcInvite) << "client" << id_ << "revoked invite" << revoke->invite;
        session_->dropInvited(revoke->invite);
        sendJson(writeServerMessage(InviteRevoked{revoke->invite}));
        return;
    }
    const auto& create = std::get<InviteCreate>(message);
    // Absent: until the session ends, which no invite outlives, at most a day.
    const auto issued =
        invites.issue(session_->id(), create.lifetimeSeconds.value_or(kMaxInviteLifetimeSeconds));
    if (!issued) {
        sendError("invite-limit",
                  "this session has issued as many invites as it may (" +
                      std::to_string(InviteBook::kMaxPerSession) + ")",
                  false);
        return;
    }
    InviteCreated created{
        issued->number, issued->code, issued->expires, "/#invite=" + issued->code, {}, {}};
    created.link = create.origin.value_or(linkOrigin()) + created.path;
    created.qr = encodeQrCode(created.link);
    qCInfo(lcInvite) << "client" << id_ << "created invite" << created.invite;
    sendJson(writeServerMessage(created));
}

// How this client reached the server: the handshake's Host, with the scheme of
// the port; the socket's own address when the Host is odd.
std::string ClientConnection::linkOrigin() const {
    const std::string scheme = server_.servesTls() ? "https://" : "http://";
    const QByteArray host = socket_ ? socket_->request().rawHeader("Host") : QByteArray();
    if (isHostAndPort(host)) {
        return scheme + host.toStdString();
    }
    QString address = socket_ ? socket_->localAddress().toString() : QString("localhost");
    if (address.contains(':')) {
        address = "[" + address + "]";
    }
    return scheme + address.toStdString() + ":" +
           std::to_string(socket_ ? socket_->localPort() : server_.port());
}

} // namespace lucent::remote
