#pragma once

#include <functional>
#include <stdexcept>
#include <stop_token>
#include <string>

namespace lucent {

// How far a scan or load has come. Sent from worker threads, one at a time.
struct LoadProgress {
    std::string stage; // "scanning", "decoding", "resampling", ...
    std::size_t done = 0;
    std::size_t total = 0;
};

struct LoadControl {
    std::function<void(const LoadProgress&)> onProgress;
    std::stop_token stop; // request_stop() on its source cancels the work
    int threads = 0;      // 0: all cores

    bool stopRequested() const { return stop.stop_requested(); }
};

// Thrown when the user cancels; nothing half-built is returned.
class LoadCancelled : public std::runtime_error {
public:
    LoadCancelled() : std::runtime_error("cancelled") {}
};

// Bad or unreadable input: the message names the file and what is wrong.
class LoadError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

} // namespace lucent
