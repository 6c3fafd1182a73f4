#pragma once
// The pointer and marks of one view (a teaching session's, or a client's own):
// the presenter's pointer goes to every member as it came (screen space, no
// render-thread work); a mark is anchored on the surface its points show, on
// the render thread, and then sent to every member, who projects the anchors
// with each frame's projection. Marks last until marks-clear or the view's
// next series; a member who joins later is sent them at once. Members whose
// connection speaks a version before 4 are sent none of this.

#include <QPointer>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "protocol/ProtocolMessages.h"
#include "server/RenderWorker.h"

namespace lucent::remote {

class ClientConnection;
class RenderServer;
class ViewStream;

class ViewMarks {
public:
    ViewMarks(ViewStream& view, RenderServer& server);

    // To every member at once.
    void point(const PointerUpdate& pointer);
    // Hides the pointer when it is shown (its presenter no longer presents).
    void hidePointer();
    // Anchors `place` (fractions of the view as `by` sees it); every member gets
    // the mark when the render thread has placed it. The error code and message
    // when it cannot be placed (no series shown, the limit reached).
    std::optional<std::pair<std::string, std::string>> place(const MarkPlace& place,
                                                             ClientConnection& by);
    // Forgets the marks (and those being anchored); marks-cleared to every member
    // when there were any, or when `always`.
    void clear(bool always);
    // The marks and the pointer, to a member who joins later.
    void sendTo(ClientConnection& member) const;
    // The render thread's anchors for a mark placed here.
    void anchored(const FoundAnchors& found);
    // The view's onlookers (followers in free look) get the marks, projected on
    // their own frames, but not the pointer, which points into the presenter's
    // view: a follower back from free look gets the pointer as it is now.
    void rejoined(ClientConnection& follower) const;

private:
    void sendToMembers(const std::string& json, bool onlookersToo) const;

    struct Pending {
        MarkPlace place;
        QPointer<ClientConnection> by;
    };
    ViewStream& view_;
    RenderServer& server_;
    std::vector<std::string> shown_;           // each mark's message, in order
    std::map<std::uint64_t, Pending> pending_; // by ticket
    std::uint64_t nextTicket_ = 1;
    std::uint64_t nextId_ = 1;
    std::string pointer_; // the last pointer message; empty while hidden
};

} // namespace lucent::remote
