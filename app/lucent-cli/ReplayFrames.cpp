#include "ReplayFrames.h"

#include <cmath>

#include "core/scene/Renderer.h"
#include "protocol/ViewMessages.h"

namespace lucent::cli {

ReplayFrames::ReplayFrames(Renderer& renderer, const Volume& volume, remote::Recording recording,
                           remote::ReplayPace pace, int framesPerSecond, int width, int height)
    : renderer_(renderer), volume_(volume), recording_(std::move(recording)), pace_(pace),
      fps_(framesPerSecond), width_(width), height_(height) {
    if (pace_ == remote::ReplayPace::Step) {
        views_ = remote::recordedViews(recording_);
        count_ = int(views_.size());
    } else {
        current_ = remote::recordedStart(recording_);
        count_ = int(recording_.header.durationMs * fps_ / 1000) + 1;
    }
}

std::int64_t ReplayFrames::frameTimeMs(int k, int framesPerSecond) {
    return std::int64_t(k) * 1000 / framesPerSecond;
}

RenderDescription ReplayFrames::framed(RenderDescription d) const {
    d.volume = &volume_;
    d.width = width_;
    d.height = height_;
    return d;
}

ImageRGBA8 ReplayFrames::frame(int k) {
    if (pace_ == remote::ReplayPace::Step) {
        return renderer_.render(framed(views_.at(std::size_t(k)))).image;
    }
    const std::int64_t at = frameTimeMs(k, fps_);
    const auto& messages = recording_.messages;
    if (applied_ > 0 && messages[applied_ - 1].atMs > at) {
        current_ = remote::recordedStart(recording_); // an earlier frame: from the start again
        applied_ = 0;
    }
    while (applied_ < messages.size() && messages[applied_].atMs <= at) {
        if (const auto error = remote::applyViewMessage(messages[applied_].message, current_)) {
            throw remote::RecordingError("recorded message " + std::to_string(applied_ + 1) + ": " +
                                         *error);
        }
        ++applied_;
    }
    return renderer_.render(framed(current_)).image;
}

} // namespace lucent::cli
