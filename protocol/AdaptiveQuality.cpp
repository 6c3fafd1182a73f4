#include "protocol/AdaptiveQuality.h"

namespace lucent::remote {

void AdaptiveQuality::record(double frameMs) {
    if (!(frameMs >= 0.0)) {
        return;
    }
    // A running average over the frames of this level, the newest weighted most.
    averageMs_ = frames_ == 0 ? frameMs : 0.5 * averageMs_ + 0.5 * frameMs;
    ++frames_;
    // One slow frame steps down at once (the user sees stutter); stepping up
    // waits for two fast ones, and "fast" leaves room for the better level
    // costing up to twice as much.
    if (averageMs_ > targetMs_ && level_ + 1 < kInteractiveLevels) {
        ++level_;
        frames_ = 0;
    } else if (frames_ >= 2 && averageMs_ < 0.45 * targetMs_ && level_ > 0) {
        --level_;
        frames_ = 0;
    }
}

} // namespace lucent::remote
