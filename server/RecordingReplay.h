#pragma once
// A recording replayed into a view whose start view the caller has set: its
// recorded messages applied at the pace they were recorded (the view's own
// pacing merges those it cannot render in time, as live), or one recorded view
// a step, each a lossless still. The client that replays is told which view
// shows in which frame (replay-progress); the owner ends it (replay-ended).

#include <QElapsedTimer>
#include <QObject>
#include <QPointer>
#include <QTimer>

#include <cstddef>
#include <functional>
#include <string>

#include "protocol/ProtocolMessages.h"
#include "server/ViewStream.h"

namespace lucent::remote {

class RecordingReplay : public QObject {
public:
    struct Hooks {
        // Applies a recorded message to the view (view messages) or its session.
        std::function<void(const ClientMessage&)> apply;
        // Tells the client that replays.
        std::function<void(const std::string& json)> tell;
        // The replay is over ("end") or its view went away ("view"): the owner
        // sends replay-ended and deletes it later.
        std::function<void(const std::string& reason)> ended;
    };
    RecordingReplay(std::string id, Recording recording, ReplayPace pace, ViewStream& view,
                    Hooks hooks);

    const std::string& id() const { return id_; }
    ReplayPace pace() const { return pace_; }
    // Reports view 0 (the start) and, at the original pace, plays on.
    void begin();
    // Stepped: applies the messages up to the next recorded view.
    void step();
    // Ended: nothing more is applied (its owner deletes it later; a timer
    // that comes first must not play on).
    void cancel();

private:
    void tick();
    void report();
    void finishWithStill();

    std::string id_;
    Recording recording_;
    ReplayPace pace_;
    QPointer<ViewStream> view_;
    Hooks hooks_;
    std::size_t next_ = 0; // the next recorded message to apply
    int shown_ = 0;        // the recorded view shown (0: the start)
    bool interacting_ = false;
    QTimer timer_;
    QElapsedTimer clock_;
    bool clockStarted_ = false;
    bool cancelled_ = false;
};

} // namespace lucent::remote
