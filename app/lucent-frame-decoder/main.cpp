// lucent-frame-decoder: decodes the frames of compressed DICOM files for Lucent,
// which starts it (core/dicom/DecoderProcess.h) so that a codec failing on a
// damaged stream cannot take down the application. It reads requests on standard
// input and answers each on standard output (core/dicom/DecoderMessages.h) until
// its input ends; it is not meant to be run by hand.
#include <algorithm>
#include <cstdint>
#include <exception>
#include <fstream>

#include <sys/resource.h>
#include <unistd.h>

#include "core/dicom/DecoderMessages.h"

namespace {

#ifndef LUCENT_NO_ADDRESS_SPACE_LIMIT
// The address space this process maps now, from /proc/self/statm (pages).
std::uint64_t mappedBytes() {
    std::ifstream statm("/proc/self/statm");
    std::uint64_t pages = 0;
    statm >> pages;
    return pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

#endif

// A damaged codestream can make OpenJPEG allocate gigabytes and touch them for
// tens of seconds before it fails (fuzz_dicom found one): the whole machine's
// memory pays, not just this process. So a request may map what decoding it can
// need (eight times its decoded frames, plus 512 MiB of codec state) beyond what
// is mapped already; an allocation past that fails at once and the codec gives up.
// Builds with AddressSanitizer leave it off: its shadow needs terabytes of address space.
void limitAddressSpace(const lucent::DecodeRequest& request) {
#ifndef LUCENT_NO_ADDRESS_SPACE_LIMIT
    const std::uint64_t frames = static_cast<std::uint64_t>(request.layout.rows) *
                                 static_cast<std::uint64_t>(request.layout.columns) *
                                 static_cast<std::uint64_t>(request.frames) *
                                 static_cast<std::uint64_t>(request.layout.bitsAllocated / 8) *
                                 static_cast<std::uint64_t>(request.layout.samplesPerPixel);
    rlimit limit{};
    ::getrlimit(RLIMIT_AS, &limit);
    const std::uint64_t wanted = mappedBytes() + 8 * frames + (std::uint64_t(512) << 20);
    limit.rlim_cur =
        limit.rlim_max == RLIM_INFINITY ? wanted : std::min<rlim_t>(wanted, limit.rlim_max);
    ::setrlimit(RLIMIT_AS, &limit);
#else
    (void)request;
#endif
}

} // namespace

#ifdef LUCENT_NO_ADDRESS_SPACE_LIMIT
// The same bound in sanitized builds, through AddressSanitizer's own limits: no
// allocation over 1 GiB, and the process stopped when it holds over 2 GiB. Its
// reports go nowhere (standard error is /dev/null; Lucent names the file), so a
// codec's crash simply ends the process: the sanitizer's own handling of a SEGV
// inside GDCM hung the child for a minute at times (fuzz_dicom timeouts).
extern "C" const char* __asan_default_options() {
    return "max_allocation_size_mb=1024:hard_rss_limit_mb=2048:symbolize=0:handle_segv=0:"
           "handle_sigbus=0:handle_abort=0:handle_sigfpe=0:handle_sigill=0";
}
extern "C" const char* __ubsan_default_options() {
    return "symbolize=0";
}
#endif

int main() {
    using namespace lucent;
    if (::isatty(STDIN_FILENO) != 0) {
        static const char usage[] = "lucent-frame-decoder: started by Lucent to decode DICOM "
                                    "frames; not meant to be run by hand\n";
        [[maybe_unused]] const auto n = ::write(STDERR_FILENO, usage, sizeof usage - 1);
        return 2;
    }
    while (const std::optional<DecodeRequest> request = readRequest(STDIN_FILENO)) {
        limitAddressSpace(*request);
        DecodeReply reply;
        try {
            reply = decodeFramesWithGdcm(request->file, request->layout, request->frames);
        } catch (const std::exception& e) {
            reply = std::string(e.what());
        }
        if (!writeReply(STDOUT_FILENO, reply)) {
            return 1;
        }
    }
    return 0;
}
