#pragma once
// A teaching session: one view, one presenter who controls it, followers who
// receive the same frames. The series shown is the de-identified copy that
// the server makes when the presenter opens one. When the presenter leaves,
// the longest-standing follower who came with a token presents; when the last
// of those leaves, the session ends (followers joined by invite never present).

#include <QList>
#include <QObject>
#include <QPointer>
#include <QString>

#include <cstdint>
#include <memory>
#include <string>

#include "core/io/SeriesEntry.h"
#include "server/FreeLookViews.h"
#include "server/ViewStream.h"

namespace lucent::remote {

class ClientConnection;
class RenderServer;

class TeachingSession : public QObject {
    Q_OBJECT
public:
    TeachingSession(QString id, ClientConnection& presenter, RenderServer& server, int maxMembers,
                    QObject* parent);

    const QString& id() const { return id_; }
    ViewStream& view() { return *view_; }
    // Followers who look on their own, and the view each watches.
    FreeLookViews& freeLook() { return *freeLook_; }
    ViewStream& viewOf(const ClientConnection& member);
    bool isPresenter(const ClientConnection& client) const { return presenter_ == &client; }
    int memberCount() const;
    bool full() const { return memberCount() >= maxMembers_; }

    // Adds a follower and gives it the series and the last frame, if any.
    void join(ClientConnection& client);
    // Removes a member; a leaving presenter hands control to the longest-
    // standing follower who came with a token. True when no such member is left:
    // the session ends.
    bool leave(ClientConnection& client);
    // The member with this client number; null when none.
    ClientConnection* member(quint64 id) const;
    // Gives control to the member with this client number; false when none.
    bool handover(quint64 to);
    // The session ends: members still in it (followers by invite) are told
    // session-left and their connections close.
    void dismissAll();
    // Members who joined by this invite are refused and their connections close.
    void dropInvited(std::uint64_t invite);
    // The presenter opens a series of the server: the members see its
    // de-identified copy once it is ready.
    void share(std::shared_ptr<const SeriesEntry> original);
    // The series last shared, as the server lists it (what a recording names).
    const std::shared_ptr<const SeriesEntry>& original() const { return original_; }

    // {"type":"session-state",...} to every member (each told its own role).
    void broadcastState();
    // {"type":"free-look-state",...} to the presenter (version 4).
    void sendFreeLookState();

private:
    void sendToAll(const std::string& json);

    QString id_;
    RenderServer& server_;
    int maxMembers_;
    ViewStream* view_;                          // child
    QList<QPointer<ClientConnection>> members_; // in the order they joined
    QPointer<ClientConnection> presenter_;
    std::shared_ptr<const SeriesEntry> original_;
    std::string openedMessage_;    // what a member who joins later is sent
    std::uint64_t shareCount_ = 0; // a later share() supersedes a pending one
    std::unique_ptr<FreeLookViews> freeLook_;
};

} // namespace lucent::remote
