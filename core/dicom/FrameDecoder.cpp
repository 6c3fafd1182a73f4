#include "core/dicom/FrameDecoder.h"

#include "core/dicom/DecoderProcess.h"

namespace lucent {

bool isJpeg2000(const std::string& transferSyntax) {
    return transferSyntax == "1.2.840.10008.1.2.4.90" || transferSyntax == "1.2.840.10008.1.2.4.91";
}

DecodedFrames decodeFrames(const std::string& file, const PixelLayout& expected, int frames) {
    // JPEG-LS goes to DCMTK alone: GDCM's JPEG-LS codec leaks its copy of the
    // stream whenever CharLS fails on it (fuzz_dicom found it), so every load
    // of a damaged file would cost a long-running server memory. The child
    // process costs time instead, and gives everything back when it exits.
    if (isJpegLs(expected.transferSyntax)) {
        return decodeJpegLsWithDcmtk(file, expected, frames);
    }
    // JPEG 2000 only in lucent-frame-decoder: on damaged codestreams GDCM's
    // codec with OpenJPEG leaks, frees what it did not allocate and writes past
    // its buffer (fuzz_dicom found all three), and no check of the codestream
    // here could promise to stop every such stream.
    if (isJpeg2000(expected.transferSyntax)) {
        return threadDecoderProcess().decode(file, expected, frames);
    }
    return decodeFramesWithGdcm(file, expected, frames);
}

} // namespace lucent
