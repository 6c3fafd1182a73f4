#pragma once
// While a client interacts, the server picks the image scale and the JPEG
// quality of each frame so that rendering plus encoding holds a target frame
// rate: it measures each frame's cost and steps along a ladder of settings,
// cheaper when frames are too slow, better when there is room. Plain C++.

#include <cstddef>
#include <iterator>

namespace lucent::remote {

struct InteractiveSetting {
    double scale = 1.0; // image side against the view's
    int jpegQuality = 85;
};

// From the best setting to the cheapest: scale 1, 0.75, 0.5, 0.35; JPEG
// quality 85 down to 60, no lower: on CT, quality 60 keeps a frame at 32 dB
// against the render (what a JPEG frame owes the client), 50 falls to 30.5.
inline constexpr InteractiveSetting kInteractiveLadder[] = {
    {1.0, 85}, {1.0, 70}, {0.75, 70}, {0.75, 60}, {0.5, 60}, {0.35, 60},
};
inline constexpr std::size_t kInteractiveLevels = std::size(kInteractiveLadder);
// 20 frames a second.
inline constexpr double kTargetFrameMs = 50.0;

class AdaptiveQuality {
public:
    explicit AdaptiveQuality(double targetFrameMs = kTargetFrameMs) : targetMs_(targetFrameMs) {}

    InteractiveSetting current() const { return kInteractiveLadder[level_]; }
    std::size_t level() const { return level_; }
    // The render and encode time of a frame made with current().
    void record(double frameMs);

private:
    double targetMs_;
    std::size_t level_ = 4; // start at half size, quality 60
    double averageMs_ = 0.0;
    int frames_ = 0; // at this level
};

} // namespace lucent::remote
