// ClientConnection: free look (docs/protocol.md, "Free look"): a follower's own
// view of the session's series, and the presenter's recall.
#include "server/ClientConnection.h"
#include "server/FreeLookViews.h"
#include "server/TeachingSession.h"
#include "server/ViewStream.h"

namespace lucent::remote {

void ClientConnection::handleFreeLook(const ClientMessage& message) {
    if (!session_) {
        sendError("out-of-order", std::string(messageType(message)) + ": not in a session", true);
        return;
    }
    FreeLookViews& looks = session_->freeLook();
    const bool presenter = session_->isPresenter(*this);
    if (std::holds_alternative<FreeLookRecall>(message)) {
        if (!presenter) {
            sendError("not-presenter", "free-look-recall: only the presenter calls followers back",
                      false);
            return;
        }
        looks.endAll("recalled", true);
        return;
    }
    if (presenter) {
        sendError("bad-request",
                  "free-look: the presenter controls the session's view; free look is for "
                  "followers",
                  false);
        return;
    }
    if (std::get<FreeLook>(message).active) {
        looks.start(*this);
    } else if (looks.viewOf(*this)) {
        looks.end(*this, "own", true);
    } else {
        // Not looking on its own: it already watches the session's view.
        sendJson(writeServerMessage(FreeLookEnded{"own"}));
    }
}

ViewStream* ClientConnection::controlledView(const ClientMessage& viewMessage) {
    if (!session_) {
        return ownView_;
    }
    if (session_->isPresenter(*this)) {
        return &session_->view();
    }
    ViewStream* own = session_->freeLook().viewOf(*this);
    return own && appliesToFreeLook(viewMessage) ? own : nullptr;
}

} // namespace lucent::remote
