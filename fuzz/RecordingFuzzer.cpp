// fuzz_recording: one input is a recorded teaching session (protocol/Recording.h),
// as lucent-server's replay and lucent-cli movie --replay read it from the store.
// It is read or refused with a RecordingError; what is accepted is written again
// line by line with the recording's own writers and must read back to the same
// lines, and its views must be made (or refused) without a crash.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "protocol/Recording.h"

namespace {

std::string written(const lucent::remote::Recording& r) {
    using namespace lucent::remote;
    std::string text = recordingHeaderLine(r.header) + "\n";
    for (const ClientMessage& m : r.start) {
        text += recordingStartLine(m) + "\n";
    }
    for (const RecordedMessage& m : r.messages) {
        text += recordedMessageLine(m.atMs, m.message) + "\n";
    }
    return text;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace lucent::remote;
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    Recording recording;
    try {
        recording = parseRecording(text, "fuzz input");
    } catch (const RecordingError&) {
        return 0;
    }
    const std::string once = written(recording);
    std::string twice;
    try {
        twice = written(parseRecording(once, "written fuzz input"));
    } catch (const RecordingError& e) {
        std::fprintf(stderr, "fuzz_recording: the written recording is refused: %s\n%s\n", e.what(),
                     once.c_str());
        std::abort();
    }
    if (twice != once) {
        std::fprintf(stderr, "fuzz_recording: the writers do not read back as themselves:\n%s\n",
                     once.c_str());
        std::abort();
    }
    try {
        (void)recordedViews(recording);
    } catch (const RecordingError&) {
        // A view message that cannot apply (a preset this build lacks): refused.
    }
    return 0;
}
