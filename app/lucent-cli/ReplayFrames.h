#pragma once
// lucent-cli movie --replay: the views of a recorded teaching session
// (protocol/Recording.h) as movie frames, rendered here. At the original pace
// frame k shows the view current k / fps seconds after the recording began;
// stepped, frame k is recorded view k (the start, then each change).

#include "core/movie/MovieFrames.h"
#include "protocol/ClientMessages.h"
#include "protocol/Recording.h"

namespace lucent::cli {

class ReplayFrames : public MovieFrames {
public:
    // `renderer` and `volume` (the recording's series) must outlive this.
    // Throws remote::RecordingError when a recorded view cannot be made.
    ReplayFrames(Renderer& renderer, const Volume& volume, remote::Recording recording,
                 remote::ReplayPace pace, int framesPerSecond, int width, int height);
    int count() const override { return count_; }
    ImageRGBA8 frame(int k) override;
    // The milliseconds after the recording's start that frame k shows (original pace).
    static std::int64_t frameTimeMs(int k, int framesPerSecond);

private:
    RenderDescription framed(RenderDescription d) const;

    Renderer& renderer_;
    const Volume& volume_;
    remote::Recording recording_;
    remote::ReplayPace pace_;
    int fps_, width_, height_;
    int count_ = 0;
    std::vector<RenderDescription> views_; // stepped
    // Original pace: the view after the first `applied_` messages.
    RenderDescription current_;
    std::size_t applied_ = 0;
};

} // namespace lucent::cli
