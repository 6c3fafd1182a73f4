#include "server/TeachingSession.h"

#include <QLoggingCategory>

#include <algorithm>

#include "server/ClientConnection.h"
#include "server/InviteBook.h"
#include "server/RenderServer.h"
#include "server/ViewMarks.h"

namespace lucent::remote {
namespace {

Q_LOGGING_CATEGORY(lcSession, "lucent.server.session")

} // namespace

TeachingSession::TeachingSession(QString id, ClientConnection& presenter, RenderServer& server,
                                 int maxMembers, QObject* parent)
    : QObject(parent), id_(std::move(id)), server_(server), maxMembers_(maxMembers),
      view_(new ViewStream(server.newViewId(), server, this)), presenter_(&presenter),
      freeLook_(std::make_unique<FreeLookViews>(*view_, server, server.maxFreeLook(), this,
                                                [this] { sendFreeLookState(); })) {
    members_.append(&presenter);
    view_->addMember(&presenter);
    view_->setPacer(&presenter);
}

int TeachingSession::memberCount() const {
    int n = 0;
    for (const auto& m : members_) {
        n += m ? 1 : 0;
    }
    return n;
}

void TeachingSession::join(ClientConnection& client) {
    members_.append(&client);
    view_->addMember(&client);
    if (!openedMessage_.empty() && view_->series()) {
        client.sendJson(openedMessage_);
        if (!view_->lastFrame().isEmpty()) {
            client.offerFrame(view_->lastFrame());
        }
        view_->marks().sendTo(client);
        view_->slices().offerLastFrames(client);
    }
}

ViewStream& TeachingSession::viewOf(const ClientConnection& member) {
    ViewStream* own = freeLook_->viewOf(member);
    return own ? *own : *view_;
}

void TeachingSession::sendFreeLookState() {
    if (presenter_ && presenter_->version() >= 4) {
        presenter_->sendJson(
            writeServerMessage(FreeLookState{freeLook_->count(), freeLook_->limit()}));
    }
}

bool TeachingSession::leave(ClientConnection& client) {
    freeLook_->end(client, "left", false);
    members_.removeAll(&client);
    members_.removeAll(nullptr);
    view_->removeMember(&client);
    if (presenter_ == &client || !presenter_) {
        const auto next = std::find_if(members_.cbegin(), members_.cend(),
                                       [](const auto& m) { return m && m->invite() == 0; });
        presenter_ = next == members_.cend() ? nullptr : next->data();
        view_->setPacer(presenter_);
        if (presenter_) {
            qCInfo(lcSession) << "session: the presenter left; client" << presenter_->id()
                              << "presents";
            freeLook_->end(*presenter_, "presenting", true);
            sendFreeLookState();
        }
    }
    view_->pump(); // a new pacer may be ready
    return presenter_ == nullptr;
}

ClientConnection* TeachingSession::member(quint64 id) const {
    for (const auto& m : members_) {
        if (m && m->id() == id) {
            return m.data();
        }
    }
    return nullptr;
}

void TeachingSession::dismissAll() {
    freeLook_->endAll("session-ended", false);
    const auto members = members_;
    members_.clear();
    for (const auto& m : members) {
        if (m) {
            view_->removeMember(m.data());
            m->sessionEnded(id_.toStdString());
        }
    }
}

void TeachingSession::dropInvited(std::uint64_t invite) {
    const auto members = members_;
    for (const auto& m : members) {
        if (m && m->invite() == invite) {
            m->sendError("auth-failed", InviteBook::refusal(InviteBook::State::Revoked), true);
        }
    }
}

bool TeachingSession::handover(quint64 to) {
    for (const auto& m : std::as_const(members_)) {
        if (m && m->id() == to) {
            freeLook_->end(*m, "presenting", true);
            presenter_ = m;
            view_->setPacer(m);
            view_->pump();
            sendFreeLookState();
            return true;
        }
    }
    return false;
}

void TeachingSession::share(std::shared_ptr<const SeriesEntry> original) {
    const std::uint64_t ticket = ++shareCount_;
    freeLook_->endAll("series", true);
    original_ = original;
    openedMessage_.clear();
    view_->reset(*original);
    server_.deidentifiedCopy(
        original, this, [this, ticket](std::shared_ptr<const SeriesEntry> copy, QString error) {
            if (ticket != shareCount_) {
                return; // the presenter opened another series meanwhile
            }
            if (!copy) {
                view_->close();
                if (presenter_) {
                    presenter_->sendError(
                        "render-failed",
                        "the series could not be de-identified: " + error.toStdString(), false);
                }
                return;
            }
            openedMessage_ = view_->show(std::move(copy));
            sendToAll(openedMessage_);
            broadcastState();
        });
}

void TeachingSession::broadcastState() {
    SessionState state;
    state.session = id_.toStdString();
    state.members = memberCount();
    for (const auto& m : std::as_const(members_)) {
        if (m) {
            state.memberIds.push_back(m->id());
        }
    }
    if (presenter_) {
        state.presenter = presenter_->id();
    }
    if (view_->series()) {
        state.series = view_->series()->id;
    }
    for (const auto& m : std::as_const(members_)) {
        if (!m) {
            continue;
        }
        state.you = m->id();
        state.role = m == presenter_ ? "presenter" : "follower";
        m->sendJson(writeServerMessage(state));
    }
}

void TeachingSession::sendToAll(const std::string& json) {
    for (const auto& m : std::as_const(members_)) {
        if (m) {
            m->sendJson(json);
        }
    }
}

} // namespace lucent::remote
