#include "server/RecordingReplay.h"

#include <algorithm>

#include "server/ClientConnection.h"

namespace lucent::remote {
namespace {

// While a session's de-identified copy is being made the view shows nothing:
// the original pace starts when it does.
constexpr int kWaitForSeriesMs = 50;

} // namespace

RecordingReplay::RecordingReplay(std::string id, Recording recording, ReplayPace pace,
                                 ViewStream& view, Hooks hooks)
    : id_(std::move(id)), recording_(std::move(recording)), pace_(pace), view_(&view),
      hooks_(std::move(hooks)) {
    timer_.setSingleShot(true);
    connect(&timer_, &QTimer::timeout, this, &RecordingReplay::tick);
}

void RecordingReplay::begin() {
    report();
    if (pace_ == ReplayPace::Original) {
        tick();
    } else if (recording_.header.views == 1) {
        hooks_.ended("end"); // the start view is all it holds
    }
}

void RecordingReplay::report() {
    if (view_) {
        hooks_.tell(
            writeServerMessage(ReplayProgress{id_, shown_, recording_.header.views, view_->seq()}));
    }
}

void RecordingReplay::cancel() {
    cancelled_ = true;
    timer_.stop();
}

void RecordingReplay::step() {
    if (cancelled_) {
        return;
    }
    if (!view_) {
        hooks_.ended("view");
        return;
    }
    const auto& messages = recording_.messages;
    while (next_ < messages.size()) {
        const ClientMessage& m = messages[next_++].message;
        // Stepped frames are stills: the drags' interaction is left out.
        if (std::holds_alternative<InteractionUpdate>(m)) {
            continue;
        }
        hooks_.apply(m);
        if (showsRecordedView(m)) {
            ++shown_;
            break;
        }
    }
    // Messages after the last view (the end of a drag) change no picture.
    const bool last = std::none_of(messages.begin() + std::ptrdiff_t(next_), messages.end(),
                                   [](const auto& r) { return showsRecordedView(r.message); });
    report();
    if (last) {
        hooks_.ended("end");
    }
}

void RecordingReplay::tick() {
    if (cancelled_) {
        return;
    }
    if (!view_ || !view_->accepting()) { // gone, or its de-identified copy failed
        hooks_.ended("view");
        return;
    }
    if (!clockStarted_) {
        if (!view_->series()) {
            timer_.start(kWaitForSeriesMs);
            return;
        }
        clock_.start();
        clockStarted_ = true;
    }
    const auto& messages = recording_.messages;
    const std::int64_t now = clock_.elapsed();
    const int before = shown_;
    while (next_ < messages.size() && messages[next_].atMs <= now) {
        const ClientMessage& m = messages[next_++].message;
        if (const auto* interaction = std::get_if<InteractionUpdate>(&m)) {
            interacting_ = interaction->active;
        }
        hooks_.apply(m);
        shown_ += showsRecordedView(m) ? 1 : 0;
    }
    if (shown_ != before) {
        report();
    }
    if (next_ < messages.size()) {
        timer_.start(int(std::clamp<std::int64_t>(messages[next_].atMs - now, 0, 60000)));
        return;
    }
    finishWithStill();
    hooks_.ended("end");
}

void RecordingReplay::finishWithStill() {
    if (interacting_) {
        // Recorded mid-drag: the replay ends on a lossless still, as a drag does.
        hooks_.apply(InteractionUpdate{false});
        interacting_ = false;
    }
}

} // namespace lucent::remote
