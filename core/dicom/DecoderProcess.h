#pragma once
// Decoding untrusted frames in a child process, lucent-frame-decoder: a codec
// that crashes, aborts, hangs or leaks on a damaged stream takes down or costs
// only the child, which is started again for the next file. One child per
// thread, kept between files so that a series pays for starting it once, and
// replaced after kRequestsPerChild files so that what codecs leak goes back.
// Private to lucent_io.

#include <chrono>
#include <string>

#include <sys/types.h>

#include "core/dicom/FrameDecoder.h"

namespace lucent {

class DecoderProcess {
public:
    static constexpr int kRequestsPerChild = 1000;
    static constexpr std::chrono::seconds kTimeout{60};

    explicit DecoderProcess(std::chrono::milliseconds timeout = kTimeout,
                            int requestsPerChild = kRequestsPerChild);
    ~DecoderProcess();
    DecoderProcess(const DecoderProcess&) = delete;
    DecoderProcess& operator=(const DecoderProcess&) = delete;

    // The frames of `file`; LoadError naming it when the decoder refuses them,
    // stops on them (a signal), or takes longer than the timeout.
    DecodedFrames decode(const std::string& file, const PixelLayout& expected, int frames);

    pid_t pid() const { return pid_; } // 0 when none runs

private:
    void start();
    void stop(); // kills a child that may be stuck; reaps it
    std::string howItEnded();

    std::chrono::milliseconds timeout_;
    int requestsPerChild_;
    pid_t pid_ = 0;
    int socket_ = -1;
    int served_ = 0; // files the running child was asked for
};

// Where lucent-frame-decoder is: $LUCENT_FRAME_DECODER, else beside the running
// program (the build tree), else in ../libexec/lucent from it (installed), else in
// the libexec folder of the build's prefix. Empty if none is there.
std::string frameDecoderExecutable();

// The calling thread's decoder process.
DecoderProcess& threadDecoderProcess();

} // namespace lucent
