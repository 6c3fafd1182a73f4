#pragma once
// The followers of a teaching session who look on their own (free look): each
// watches its own ViewStream, a copy of the session's view that keeps following
// the presenter's transfer function, mode, clip and sampling but has the
// follower's own camera, size and interaction. At most `limit` at once. Ending
// free look (by the follower, a recall, a new series, ...) tells the follower
// why and gives it the session's newest frame at once: the very bytes the
// presenter was sent.

#include <QList>
#include <QPointer>

#include <functional>
#include <string>

#include "protocol/ProtocolMessages.h"

namespace lucent::remote {

class ClientConnection;
class RenderServer;
class ViewStream;

class FreeLookViews {
public:
    // `changed` runs whenever the number looking changes (the presenter is told).
    FreeLookViews(ViewStream& session, RenderServer& server, int limit, QObject* owner,
                  std::function<void()> changed);
    ~FreeLookViews();
    FreeLookViews(const FreeLookViews&) = delete;
    FreeLookViews& operator=(const FreeLookViews&) = delete;

    int count() const { return int(looking_.size()); }
    int limit() const { return limit_; }
    // The follower's own view; null when it follows the session.
    ViewStream* viewOf(const ClientConnection& follower) const;

    // Starts the follower's free look: free-look-started, then frames of its own
    // view. An error reply (not fatal) when it cannot: the limit, no series yet.
    void start(ClientConnection& follower);
    // Ends it, when on: free-look-ended with `reason`; when `rejoin`, the
    // follower watches the session's view again and gets its newest frame.
    void end(ClientConnection& follower, const std::string& reason, bool rejoin);
    void endAll(const std::string& reason, bool rejoin);
    // The presenter's transfer function, mode, clip or sampling: every own view follows.
    void follow(const ClientMessage& presenterMessage);

private:
    struct Look {
        QPointer<ClientConnection> follower;
        ViewStream* view; // child of the owner; deleted later when the look ends
    };

    ViewStream& session_;
    RenderServer& server_;
    int limit_;
    QObject* owner_;
    std::function<void()> changed_;
    QList<Look> looking_;
};

// Whether a follower's view message applies to its own view in free look (camera,
// size, render, interaction); the others stay the presenter's.
bool appliesToFreeLook(const ClientMessage& message);
// Whether a presenter's view message is followed by every free look (tf, mode, clip, sampling).
bool followedByFreeLook(const ClientMessage& message);

} // namespace lucent::remote
