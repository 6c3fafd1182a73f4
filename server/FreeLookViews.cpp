#include "server/FreeLookViews.h"

#include <QLoggingCategory>

#include <algorithm>

#include "server/ClientConnection.h"
#include "server/RenderServer.h"
#include "server/ViewMarks.h"
#include "server/ViewStream.h"

namespace lucent::remote {
namespace {

Q_LOGGING_CATEGORY(lcFreeLook, "lucent.server.freelook")

// free-look-started for a view: the seq of its next frame and its camera.
FreeLookStarted started(const ViewStream& view) {
    const Camera& c = view.camera();
    return {view.seq(), c.azimuth, c.elevation, c.zoom, c.distance, c.panRight, c.panUp};
}

} // namespace

bool appliesToFreeLook(const ClientMessage& message) {
    return std::holds_alternative<CameraUpdate>(message) ||
           std::holds_alternative<SizeUpdate>(message) ||
           std::holds_alternative<RenderRequest>(message) ||
           std::holds_alternative<InteractionUpdate>(message);
}

bool followedByFreeLook(const ClientMessage& message) {
    return std::holds_alternative<TransferFunctionUpdate>(message) ||
           std::holds_alternative<ModeUpdate>(message) ||
           std::holds_alternative<ClipUpdate>(message) ||
           std::holds_alternative<SamplingUpdate>(message);
}

FreeLookViews::FreeLookViews(ViewStream& session, RenderServer& server, int limit, QObject* owner,
                             std::function<void()> changed)
    : session_(session), server_(server), limit_(limit), owner_(owner),
      changed_(std::move(changed)) {}

FreeLookViews::~FreeLookViews() = default; // the views are the owner's children

ViewStream* FreeLookViews::viewOf(const ClientConnection& follower) const {
    for (const Look& look : looking_) {
        if (look.follower == &follower) {
            return look.view;
        }
    }
    return nullptr;
}

void FreeLookViews::start(ClientConnection& follower) {
    if (ViewStream* own = viewOf(follower)) {
        follower.sendJson(writeServerMessage(started(*own)));
        return; // already on
    }
    if (!session_.series()) {
        follower.sendError("bad-request", "free-look: the session shows no series yet", false);
        return;
    }
    if (count() >= limit_) {
        follower.sendError("free-look-limit",
                           "free-look: " + std::to_string(limit_) +
                               " members of this session already look on their own, as many "
                               "as the server allows",
                           false);
        return;
    }
    session_.removeMember(&follower);
    session_.addOnlooker(&follower);
    auto* own = new ViewStream(server_.newViewId(), server_, owner_);
    own->addMember(&follower);
    own->setPacer(&follower);
    looking_.append({&follower, own});
    follower.sendJson(writeServerMessage(started(session_)));
    own->startAsCopyOf(session_);
    qCInfo(lcFreeLook) << "client" << follower.id() << "looks on its own;" << count()
                       << "in free look";
    changed_();
}

void FreeLookViews::end(ClientConnection& follower, const std::string& reason, bool rejoin) {
    const auto it = std::find_if(looking_.begin(), looking_.end(),
                                 [&](const Look& look) { return look.follower == &follower; });
    if (it == looking_.end()) {
        return;
    }
    ViewStream* own = it->view;
    looking_.erase(it);
    own->removeMember(&follower);
    own->deleteLater(); // a frame in flight for it finds no member
    follower.sendJson(writeServerMessage(FreeLookEnded{reason}));
    session_.removeOnlooker(&follower);
    if (rejoin) {
        session_.addMember(&follower);
        if (!session_.lastFrame().isEmpty()) {
            follower.offerFrame(session_.lastFrame()); // replaces an own frame not yet sent
        }
        session_.marks().rejoined(follower);
    }
    qCInfo(lcFreeLook) << "client" << follower.id() << "free look ended:" << reason.c_str();
    changed_();
}

void FreeLookViews::endAll(const std::string& reason, bool rejoin) {
    const QList<Look> all = looking_;
    for (const Look& look : all) {
        if (look.follower) {
            end(*look.follower, reason, rejoin);
        }
    }
    for (const Look& look : std::as_const(looking_)) {
        look.view->deleteLater(); // of followers already gone
    }
    if (!looking_.isEmpty()) {
        looking_.clear();
        changed_();
    }
}

void FreeLookViews::follow(const ClientMessage& presenterMessage) {
    if (!followedByFreeLook(presenterMessage)) {
        return;
    }
    for (const Look& look : std::as_const(looking_)) {
        (void)look.view->apply(presenterMessage); // it applied to the session's view
    }
}

} // namespace lucent::remote
