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

namespace lucent::remote {

class ClientConnection;
class RenderServer;

class ViewStream : public QObject {
    Q_OBJECT
public:
    ViewStream(quint64 id, RenderServer& server, QObject* parent);
    ~ViewStream() override;

    quint64 id() const { return id_; }
    const std::shared_ptr<const SeriesEntry>& series() const { return series_; }
    std::uint64_t seq() const { return seq_; }
    // What the view shows now (its volume null): a recording's start.
    const RenderDescription& description() const { return description_; }
    // The last frame sent (for members who join later); empty before the first.
    const QByteArray& lastFrame() const { return lastFrame_; }

    void addMember(ClientConnection* client);
    void removeMember(ClientConnection* client);
    int memberCount() const;
    // The member whose sending paces the renders.
    void setPacer(ClientConnection* client) { pacer_ = client; }

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
    QByteArray lastFrame_;
};

} // namespace lucent::remote
