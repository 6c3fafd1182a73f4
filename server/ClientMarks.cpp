// ClientConnection: the presenter's pointer, marks and marks-clear (version 4).
// A client on its own presents its own view; in a session only the presenter
// marks (followers: not-presenter; followers by invite are refused before, as
// for everything but following).
#include "server/ClientConnection.h"
#include "server/TeachingSession.h"
#include "server/ViewMarks.h"
#include "server/ViewStream.h"

namespace lucent::remote {

bool ClientConnection::handleMark(const ClientMessage& message) {
    const auto* pointer = std::get_if<PointerUpdate>(&message);
    const auto* mark = std::get_if<MarkPlace>(&message);
    if (!pointer && !mark && !std::holds_alternative<MarksClear>(message)) {
        return false;
    }
    if (session_ && !session_->isPresenter(*this)) {
        sendError("not-presenter",
                  std::string(messageType(message)) +
                      ": only the presenter of the session points and marks",
                  false);
        return true;
    }
    ViewMarks& marks = (session_ ? session_->view() : *ownView_).marks();
    if (pointer) {
        if (!pointerClock_.isValid()) {
            pointerClock_.start();
        }
        const double seconds = double(pointerClock_.restart()) / 1000.0;
        pointerTokens_ = std::min(kCameraBurst, pointerTokens_ + seconds * kCameraPerSecond);
        if (pointerTokens_ < 1.0) {
            sendError("rate-limited", "too many pointer updates; this one was dropped", false);
            return true;
        }
        pointerTokens_ -= 1.0;
        marks.point(*pointer);
    } else if (mark) {
        if (const auto refused = marks.place(*mark, *this)) {
            sendError(refused->first, refused->second, false);
            return true;
        }
    } else {
        marks.clear(true);
    }
    recordAccepted(message); // a recording keeps the pointer and the marks with their times
    return true;
}

} // namespace lucent::remote
