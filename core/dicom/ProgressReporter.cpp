#include "core/dicom/ProgressReporter.h"

#include <algorithm>

#include <omp.h>

namespace lucent {

ProgressReporter::ProgressReporter(const LoadControl& control, std::string stage, std::size_t total)
    : control_(control), stage_(std::move(stage)), total_(total),
      every_(std::max<std::size_t>(1, total / 100)) {}

void ProgressReporter::step() {
    const std::size_t done = ++done_;
    if (!control_.onProgress || (done % every_ != 0 && done != total_)) {
        return;
    }
    const std::lock_guard lock(mutex_);
    control_.onProgress(LoadProgress{stage_, done, total_});
}

int workerThreads(const LoadControl& control) {
    return control.threads > 0 ? control.threads : omp_get_max_threads();
}

} // namespace lucent
