#pragma once
// One view that clients watch: its series, its render description, the frame
// it owes, and the clients it delivers frames to. A client on its own watches
// its own view; the members of a teaching session watch the session's. Each
// change is rendered and encoded once and the same bytes go to every member.
// At most one frame is being rendered; the next starts only when the pacing
// member (the owner, or the presenter) has sent the previous one, and every
// member is only ever sent the newest frame (stale ones are replaced, never
// queued).

#include <QByteArray>
#include <QList>
#include <QObject>
#include <QPointer>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "core/io/SeriesEntry.h"
#include "core/scene/RenderDescription.h"
#include "protocol/AdaptiveQuality.h"
#include "protocol/ProtocolMessages.h"
#include "server/RenderWorker.h"
#include "server/SliceStream.h"

namespace lucent::remote {

class ClientConnection;
class RenderServer;
class ViewMarks;

class ViewStream : public QObject {
    Q_OBJECT
public:
    ViewStream(quint64 id, RenderServer& server, QObject* parent);
    ~ViewStream() override;

    quint64 id() const { return id_; }
    const std::shared_ptr<const SeriesEntry>& series() const { return series_; }
    std::uint64_t seq() const { return seq_; }
    const Camera& camera() const { return description_.camera; }
    // The last frame sent (for members who join later); empty before the first.
    const QByteArray& lastFrame() const { return lastFrame_; }

    const QList<QPointer<ClientConnection>>& members() const { return members_; }
    // Followers of this (a session's) view who look on their own (free look):
    // they still get its marks and slices, not its frames or its pointer.
    void addOnlooker(ClientConnection* client);
    void removeOnlooker(ClientConnection* client);
    const QList<QPointer<ClientConnection>>& onlookers() const { return onlookers_; }
    const RenderDescription& description() const { return description_; }
    // Its pointer and marks (ViewMarks.h); a new series clears them.
    ViewMarks& marks() { return *marks_; }

    void addMember(ClientConnection* client);
    void removeMember(ClientConnection* client);
    int memberCount() const;
    // The member whose sending paces the renders.
    // (A new presenter: the last one's pointer is hidden.)
    void setPacer(ClientConnection* client);
    // A follower's free look: the view starts as `session`'s (series, description,
    // quality, seq) and owes a frame; its renders wait for an idle render thread
    // and may be cheaper when it is busy (RenderServer::submit()).
    void startAsCopyOf(const ViewStream& session);
    ClientConnection* pacer() const { return pacer_; }
    // Its MPR slices (version 4), reset with the series.
    SliceStream& slices() { return *slices_; }

    // open() = reset() + show(). Returns the {"type":"opened"} message (no
    // description: it may identify a patient).
    std::string open(std::shared_ptr<const SeriesEntry> series);
    // Resets the view for a series like this one (camera, mode dvr, no clip,
    // still, default preset, default sampling; the size is kept) and owes a frame; view
    // messages apply from now on, frames start once show() gives the series
    // (a teaching session's de-identified copy takes a while).
    void reset(const SeriesEntry& like);
    std::string show(std::shared_ptr<const SeriesEntry> series);
    // Forgets the series (no frames until the next open).
    void close();
    // Whether view messages apply: a series is open or being prepared.
    bool accepting() const { return series_ || opening_; }
    // Applies a view message (isViewMessage()); owes a frame. Returns an error
    // message (bad-request, not fatal) when the message cannot apply.
    std::optional<std::string> apply(const ClientMessage& message);

    // Starts the next render when one is owed and the pacer has sent the last frame.
    void pump();
    // A frame the render thread finished for this view.
    void deliver(const RenderedFrame& frame);

private:
    void changed();

    quint64 id_;
    RenderServer& server_;
    QList<QPointer<ClientConnection>> members_;
    QList<QPointer<ClientConnection>> onlookers_;
    QPointer<ClientConnection> pacer_;

    std::shared_ptr<const SeriesEntry> series_;
    bool opening_ = false;
    std::string preset_;
    RenderDescription description_; // volume stays null: the render thread fills it in
    Quality quality_ = Quality::Still;
    bool interacting_ = false;
    bool stillOwed_ = false; // the end of an interaction owes one lossless frame
    AdaptiveQuality adaptive_;
    std::uint64_t seq_ = 0; // accepted view changes so far
    bool renderInFlight_ = false;
    bool adaptiveInFlight_ = false; // the frame in flight was made with adaptive_
    bool renderWanted_ = false;
    bool background_ = false;  // free look (startAsCopyOf)
    bool upgradeOwed_ = false; // a still came degraded: the full one follows
    QByteArray lastFrame_;
    std::unique_ptr<ViewMarks> marks_;
    std::unique_ptr<SliceStream> slices_;
};

} // namespace lucent::remote
