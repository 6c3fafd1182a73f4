#pragma once
// The first error of a parallel decode, named by its file: workers record, and once they
// have joined, throwIfAny reports a cancel or that error. Shared by the volume and the
// stack loaders.

#include <exception>
#include <mutex>
#include <optional>
#include <string>

#include "core/io/LoadControl.h"

namespace lucent {

class FirstDecodeError {
public:
    void record(const std::string& file, const std::exception& e) {
        const std::lock_guard lock(mutex_);
        if (!error_) {
            const std::string what = e.what();
            error_ = what.rfind(file, 0) == 0 ? what : file + ": " + what;
        }
    }

    // Throws LoadCancelled when a stop was requested, else LoadError with the first error.
    void throwIfAny(const LoadControl& control) const {
        if (control.stopRequested()) {
            throw LoadCancelled();
        }
        if (error_) {
            throw LoadError(*error_);
        }
    }

private:
    std::mutex mutex_;
    std::optional<std::string> error_;
};

} // namespace lucent
