#include "core/dicom/FrameDecoder.h"

#include <cstdio>
#include <memory>

#include <gdcmImage.h>
#include <gdcmImageReader.h>

#include "core/io/LoadControl.h"

namespace lucent {

RawFormat rawFormatOf(const PixelLayout& layout) {
    return {layout.bitsAllocated, layout.bitsStored, layout.highBit, layout.isSigned};
}

namespace {

DecodedFrames decodeFramesWithGdcm(const std::string& file, const PixelLayout& expected) {
    gdcm::ImageReader reader;
    reader.SetFileName(file.c_str());
    if (!reader.Read()) {
        throw LoadError(file +
                        ": GDCM cannot read the image (corrupt file or unsupported encoding)");
    }
    const gdcm::Image& image = reader.GetImage();
    const gdcm::PixelFormat& pf = image.GetPixelFormat();
    if (pf.GetSamplesPerPixel() != 1) {
        throw LoadError(file + ": decoded to " + std::to_string(pf.GetSamplesPerPixel()) +
                        " samples per pixel; only greyscale is supported");
    }
    if (static_cast<int>(image.GetColumns()) != expected.columns ||
        static_cast<int>(image.GetRows()) != expected.rows) {
        throw LoadError(file + ": decoded image is " + std::to_string(image.GetColumns()) + "x" +
                        std::to_string(image.GetRows()) + ", header says " +
                        std::to_string(expected.columns) + "x" + std::to_string(expected.rows));
    }
    DecodedFrames out;
    out.format = {pf.GetBitsAllocated(), pf.GetBitsStored(), pf.GetHighBit(),
                  pf.GetPixelRepresentation() == 1};
    out.buffer.resize(image.GetBufferLength());
    if (!image.GetBuffer(out.buffer.data())) {
        throw LoadError(
            file + ": pixel data could not be decoded (" +
            std::string(reader.GetFile().GetHeader().GetDataSetTransferSyntax().GetString()
                            ? reader.GetFile().GetHeader().GetDataSetTransferSyntax().GetString()
                            : "unknown transfer syntax") +
            ")");
    }
    out.frameBytes = static_cast<std::size_t>(expected.rows) * expected.columns *
                     static_cast<std::size_t>(out.format.bitsAllocated / 8);
    return out;
}

} // namespace

DecodedFrames decodeFrames(const std::string& file, const PixelLayout& expected, int frames) {
    try {
        return decodeFramesWithGdcm(file, expected);
    } catch (const LoadError& gdcmError) {
        if (!isJpegLs(expected.transferSyntax)) {
            throw;
        }
        try {
            return decodeJpegLsWithDcmtk(file, expected, frames);
        } catch (const LoadError&) {
            throw gdcmError; // GDCM's reason is the one to report
        }
    }
}

void readNativeFrame(const std::string& file, std::uint64_t offset, std::size_t bytes, void* dst) {
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"),
                                                            &std::fclose);
    if (!f) {
        throw LoadError(file + ": cannot open for reading");
    }
    // Unbuffered: the read goes straight into dst.
    std::setvbuf(f.get(), nullptr, _IONBF, 0);
    if (std::fseek(f.get(), static_cast<long>(offset), SEEK_SET) != 0 ||
        std::fread(dst, 1, bytes, f.get()) != bytes) {
        throw LoadError(file + ": pixel data ends early (file shorter than its header says)");
    }
}

} // namespace lucent
