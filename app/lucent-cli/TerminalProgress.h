#pragma once

#include "core/io/LoadControl.h"

namespace lucent::cli {

// A LoadControl that shows "scanning 40/140" on stderr when stderr is a
// terminal (and nothing when it is a file or a pipe). Call finish() to clear the line.
class TerminalProgress {
public:
    TerminalProgress();
    const LoadControl& control() const { return control_; }
    void finish() const;

private:
    LoadControl control_;
    bool enabled_ = false;
};

} // namespace lucent::cli
