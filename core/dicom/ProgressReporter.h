#pragma once

#include <atomic>
#include <mutex>
#include <string>

#include "core/io/LoadControl.h"

namespace lucent {

// Counts finished work items from any thread and calls the user's callback,
// one call at a time, at most about a hundred times per stage.
class ProgressReporter {
public:
    ProgressReporter(const LoadControl& control, std::string stage, std::size_t total);
    void step();

private:
    const LoadControl& control_;
    std::string stage_;
    std::size_t total_;
    std::size_t every_;
    std::atomic<std::size_t> done_{0};
    std::mutex mutex_;
};

// How many threads parallel loops use for this control.
int workerThreads(const LoadControl& control);

} // namespace lucent
