#pragma once
// Getting the stored pixel values of DICOM frames: read straight from the file
// for uncompressed little-endian data, decoded by GDCM's codecs for everything
// else but JPEG-LS (DCMTK's dcmdjpls), always in a child process (DecoderProcess.h).
// Private to lucent_io and lucent-frame-decoder.

#include <cstdint>
#include <string>
#include <vector>

#include "core/io/SeriesEntry.h"

namespace lucent {

// Stored-value layout of a decoded buffer (it may differ from the header for some codecs).
struct RawFormat {
    int bitsAllocated = 16;
    int bitsStored = 16;
    int highBit = 15;
    bool isSigned = false;
};

RawFormat rawFormatOf(const PixelLayout& layout);

// Every frame of one file, decoded. Throws LoadError naming the file.
struct DecodedFrames {
    std::vector<char> buffer;
    RawFormat format;
    std::size_t frameBytes = 0;
    // Colour: what the samples are after decoding (a codec may turn YBR into RGB)
    // and how they are laid out.
    std::string photometric = "MONOCHROME2";
    int planarConfiguration = 0;
    const char* frame(int index) const { return buffer.data() + frameBytes * index; }
};
// Every frame of one compressed file, by the decoder its transfer syntax needs.
DecodedFrames decodeFrames(const std::string& file, const PixelLayout& expected, int frames);

// GDCM's codecs in this process (GdcmFrameCodec.cpp).
DecodedFrames decodeFramesWithGdcm(const std::string& file, const PixelLayout& expected,
                                   int frames);

bool isJpegLs(const std::string& transferSyntax);
DecodedFrames decodeJpegLsWithDcmtk(const std::string& file, const PixelLayout& expected,
                                    int frames);

// Reads bytes at offset into dst. Throws LoadError naming the file.
void readNativeFrame(const std::string& file, std::uint64_t offset, std::size_t bytes, void* dst);

} // namespace lucent
