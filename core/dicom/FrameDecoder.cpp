#include "core/dicom/FrameDecoder.h"

#include "core/dicom/DecoderProcess.h"

namespace lucent {

DecodedFrames decodeFrames(const std::string& file, const PixelLayout& expected, int frames) {
    // JPEG-LS goes to DCMTK alone: GDCM's JPEG-LS codec leaks its copy of the
    // stream whenever CharLS fails on it (fuzz_dicom found it), so every load
    // of a damaged file would cost a long-running server memory. The child
    // process costs time instead, and gives everything back when it exits.
    if (isJpegLs(expected.transferSyntax)) {
        return decodeJpegLsWithDcmtk(file, expected, frames);
    }
    // Everything else GDCM decodes, only in lucent-frame-decoder: on damaged
    // data GDCM's codecs (and OpenJPEG under them) leak, free what they did not
    // allocate, write past their buffers and abort on their assertions
    // (fuzz_dicom found each), and no check here could promise to stop them all.
    return threadDecoderProcess().decode(file, expected, frames);
}

} // namespace lucent
