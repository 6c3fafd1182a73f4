#include "core/dicom/FrameDecoder.h"

#include <cstdio>
#include <memory>

#include <gdcmImage.h>
#include <gdcmReader.h>

#include "core/io/LoadControl.h"

namespace lucent {

RawFormat rawFormatOf(const PixelLayout& layout) {
    return {layout.bitsAllocated, layout.bitsStored, layout.highBit, layout.isSigned};
}

namespace {

// Only GDCM's codecs see the file, never its ImageReader: that one derives the
// geometry again with ImageHelper, whose assertions abort the whole process on
// elements it does not expect (a frame count of another VR, an RT dose grid
// offset vector shorter than its frames). The geometry comes from the scan,
// which has validated it already.
gdcm::Image imageToDecode(const std::string& file, const gdcm::File& parsed,
                          const PixelLayout& expected, int frames) {
    const gdcm::Tag pixelData(0x7fe0, 0x0010);
    const gdcm::DataSet& ds = parsed.GetDataSet();
    if (!ds.FindDataElement(pixelData) || ds.GetDataElement(pixelData).IsEmpty()) {
        throw LoadError(file + ": no pixel data (7FE0,0010)");
    }
    gdcm::Image image;
    image.SetNumberOfDimensions(frames > 1 ? 3 : 2);
    image.SetDimension(0, static_cast<unsigned>(expected.columns));
    image.SetDimension(1, static_cast<unsigned>(expected.rows));
    if (frames > 1) {
        image.SetDimension(2, static_cast<unsigned>(frames));
    }
    image.SetPixelFormat(gdcm::PixelFormat(1, static_cast<unsigned short>(expected.bitsAllocated),
                                           static_cast<unsigned short>(expected.bitsStored),
                                           static_cast<unsigned short>(expected.highBit),
                                           expected.isSigned ? 1 : 0));
    image.SetPhotometricInterpretation(gdcm::PhotometricInterpretation::MONOCHROME2);
    image.SetTransferSyntax(parsed.GetHeader().GetDataSetTransferSyntax());
    image.SetDataElement(ds.GetDataElement(pixelData));
    return image;
}

DecodedFrames decodeFramesWithGdcm(const std::string& file, const PixelLayout& expected,
                                   int frames) {
    gdcm::Reader reader;
    reader.SetFileName(file.c_str());
    if (!reader.Read()) {
        throw LoadError(file +
                        ": GDCM cannot read the image (corrupt file or unsupported encoding)");
    }
    const gdcm::Image image = imageToDecode(file, reader.GetFile(), expected, frames);
    const gdcm::PixelFormat& pf = image.GetPixelFormat();
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
        return decodeFramesWithGdcm(file, expected, frames);
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
