#include "TerminalProgress.h"

#include <cstdio>

#include <unistd.h>

namespace lucent::cli {

TerminalProgress::TerminalProgress() : enabled_(::isatty(STDERR_FILENO) == 1) {
    if (enabled_) {
        control_.onProgress = [](const LoadProgress& p) {
            std::fprintf(stderr, "\r%s %zu/%zu   ", p.stage.c_str(), p.done, p.total);
            std::fflush(stderr);
        };
    }
}

void TerminalProgress::finish() const {
    if (enabled_) {
        std::fprintf(stderr, "\r\033[K");
        std::fflush(stderr);
    }
}

} // namespace lucent::cli
