#include "server/ViewMarks.h"

#include "server/ClientConnection.h"
#include "server/RenderServer.h"
#include "server/ViewStream.h"

namespace lucent::remote {
namespace {

// Pointer and marks came with version 4.
constexpr int kMarksVersion = 4;

} // namespace

ViewMarks::ViewMarks(ViewStream& view, RenderServer& server) : view_(view), server_(server) {}

void ViewMarks::sendToMembers(const std::string& json, bool onlookersToo) const {
    for (const auto& member : view_.members()) {
        if (member && member->version() >= kMarksVersion) {
            member->sendJson(json);
        }
    }
    if (onlookersToo) {
        for (const auto& onlooker : view_.onlookers()) {
            if (onlooker && onlooker->version() >= kMarksVersion) {
                onlooker->sendJson(json);
            }
        }
    }
}

void ViewMarks::rejoined(ClientConnection& follower) const {
    if (!pointer_.empty() && follower.version() >= kMarksVersion) {
        follower.sendJson(pointer_);
    }
}

void ViewMarks::point(const PointerUpdate& pointer) {
    const std::string json = writeServerMessage(PointerShown{pointer.at});
    pointer_ = pointer.at ? json : std::string();
    sendToMembers(json, false);
}

void ViewMarks::hidePointer() {
    if (!pointer_.empty()) {
        point(PointerUpdate{});
    }
}

std::optional<std::pair<std::string, std::string>> ViewMarks::place(const MarkPlace& place,
                                                                    ClientConnection& by) {
    if (!view_.series()) {
        return std::pair<std::string, std::string>("bad-request",
                                                   "mark: the view shows no series yet");
    }
    if (shown_.size() + pending_.size() >= kMaxMarks) {
        return std::pair<std::string, std::string>(
            "mark-limit", "mark: the view holds " + std::to_string(kMaxMarks) +
                              " marks, as many as it may (marks-clear removes them)");
    }
    const std::uint64_t ticket = nextTicket_++;
    pending_[ticket] = {place, &by};
    server_.submitAnchors({view_.id(), ticket, view_.series(), view_.description(), place.points});
    return std::nullopt;
}

void ViewMarks::anchored(const FoundAnchors& found) {
    const auto it = pending_.find(found.ticket);
    if (it == pending_.end()) {
        return; // cleared, or another series opened, meanwhile
    }
    const Pending pending = std::move(it->second);
    pending_.erase(it);
    if (!found.error.isEmpty()) {
        if (pending.by) {
            pending.by->sendError("render-failed", "mark: " + found.error.toStdString(), false);
        }
        return;
    }
    shown_.push_back(writeServerMessage(
        MarkShown{nextId_++, pending.place.kind, found.anchors, pending.place.text}));
    sendToMembers(shown_.back(), true);
}

void ViewMarks::clear(bool always) {
    const bool had = !shown_.empty() || !pending_.empty();
    shown_.clear();
    pending_.clear();
    if (had || always) {
        sendToMembers(writeServerMessage(MarksCleared{}), true);
    }
}

void ViewMarks::sendTo(ClientConnection& member) const {
    if (member.version() < kMarksVersion) {
        return;
    }
    for (const std::string& mark : shown_) {
        member.sendJson(mark);
    }
    if (!pointer_.empty()) {
        member.sendJson(pointer_);
    }
}

} // namespace lucent::remote
