// lucent-frame-decoder: decodes the frames of compressed DICOM files for Lucent,
// which starts it (core/dicom/DecoderProcess.h) so that a codec failing on a
// damaged stream cannot take down the application. It reads requests on standard
// input and answers each on standard output (core/dicom/DecoderMessages.h) until
// its input ends; it is not meant to be run by hand.
#include <exception>

#include <unistd.h>

#include "core/dicom/DecoderMessages.h"

int main() {
    using namespace lucent;
    if (::isatty(STDIN_FILENO) != 0) {
        static const char usage[] = "lucent-frame-decoder: started by Lucent to decode DICOM "
                                    "frames; not meant to be run by hand\n";
        [[maybe_unused]] const auto n = ::write(STDERR_FILENO, usage, sizeof usage - 1);
        return 2;
    }
    while (const std::optional<DecodeRequest> request = readRequest(STDIN_FILENO)) {
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
