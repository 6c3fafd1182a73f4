// GDCM's codecs on frames whose layout the scan has validated: everything but
// JPEG-LS (JpegLsDecoder.cpp). Lucent runs them only inside lucent-frame-decoder
// (DecoderProcess.cpp).
#include "core/dicom/DataSetStream_p.h"
#include "core/dicom/FrameDecoder.h"

#include <algorithm>
#include <cstdio>
#include <memory>

#include <gdcmImage.h>
#include <gdcmReader.h>
#include <gdcmSequenceOfFragments.h>

#include "core/io/LoadControl.h"

namespace lucent {

RawFormat rawFormatOf(const PixelLayout& layout) {
    return {layout.bitsAllocated, layout.bitsStored, layout.highBit, layout.isSigned};
}

namespace {

// GDCM's names are padded to an even length ("RGB ").
std::string trimmedPhotometric(std::string name) {
    while (!name.empty() && name.back() == ' ') {
        name.pop_back();
    }
    return name;
}

// The JPEG (ISO 10918) transfer syntaxes, decoded by GDCM's JPEG codec.
bool isJpegProcess(const std::string& transferSyntax) {
    return transferSyntax == "1.2.840.10008.1.2.4.50" ||
           transferSyntax == "1.2.840.10008.1.2.4.51" ||
           transferSyntax == "1.2.840.10008.1.2.4.57" || transferSyntax == "1.2.840.10008.1.2.4.70";
}

// The header of one JPEG frame (a fragment that starts with SOI) up to its
// scan: every marker segment inside the fragment, a start-of-frame whose size
// and component count are the image's. Empty when it is sound, else why not.
std::string jpegFrameHeaderProblem(const unsigned char* p, std::size_t n,
                                   const PixelLayout& expected) {
    std::size_t at = 2; // after SOI
    bool sawFrame = false;
    while (at + 4 <= n) {
        if (p[at] != 0xff) {
            return "no marker at byte " + std::to_string(at) + " of the JPEG header";
        }
        const unsigned marker = p[at + 1];
        if (marker == 0xff) {
            ++at; // fill byte
            continue;
        }
        const std::size_t length = std::size_t(p[at + 2]) << 8 | p[at + 3];
        if (length < 2 || at + 2 + length > n) {
            return "a JPEG marker segment runs past its fragment";
        }
        const bool startOfFrame =
            marker >= 0xc0 && marker <= 0xcf && marker != 0xc4 && marker != 0xc8 && marker != 0xcc;
        if (startOfFrame) {
            if (length < 8) {
                return "a JPEG start-of-frame segment is too short";
            }
            const int rows = p[at + 5] << 8 | p[at + 6];
            const int columns = p[at + 7] << 8 | p[at + 8];
            const int components = p[at + 9];
            if (rows != expected.rows || columns != expected.columns ||
                components != expected.samplesPerPixel) {
                return "the JPEG frame is " + std::to_string(columns) + "x" + std::to_string(rows) +
                       " with " + std::to_string(components) + " component(s), the header says " +
                       std::to_string(expected.columns) + "x" + std::to_string(expected.rows) +
                       " with " + std::to_string(expected.samplesPerPixel);
            }
            sawFrame = true;
        }
        if (marker == 0xda) { // start of scan: entropy-coded data follow
            return sawFrame ? std::string() : "a JPEG scan without a start-of-frame";
        }
        at += 2 + length;
    }
    return "a JPEG header without a scan";
}

// GDCM's JPEG codec leaks its decompressor (up to about 750 KB) when it gives
// up on a stream: one that ends before its end-of-image marker, or whose size
// is not the image's. Such streams are refused first: each frame starts with
// SOI and a sound header, and ends with EOI (FF D9, then perhaps padding),
// the last fragment included.
void checkJpegFrames(const std::string& file, const gdcm::DataElement& pixels,
                     const PixelLayout& expected, int frames) {
    const gdcm::SequenceOfFragments* fragments = pixels.GetSequenceOfFragments();
    if (fragments == nullptr || fragments->GetNumberOfFragments() == 0) {
        throw LoadError(file + ": JPEG pixel data (7FE0,0010) holds no fragments");
    }
    const std::string where = file + ": JPEG pixel data (7FE0,0010): ";
    std::size_t starts = 0;
    std::size_t ends = 0;
    bool lastEnds = false;
    const std::size_t count = fragments->GetNumberOfFragments();
    for (std::size_t i = 0; i < count; ++i) {
        const gdcm::ByteValue* bv = fragments->GetFragment(static_cast<unsigned>(i)).GetByteValue();
        const auto* p = bv ? reinterpret_cast<const unsigned char*>(bv->GetPointer()) : nullptr;
        std::size_t n = bv ? static_cast<std::size_t>(bv->GetLength()) : std::size_t(0);
        if (n >= 2 && p[0] == 0xff && p[1] == 0xd8) {
            if (const std::string why = jpegFrameHeaderProblem(p, n, expected); !why.empty()) {
                throw LoadError(where + "frame " + std::to_string(starts + 1) + ": " + why);
            }
            ++starts;
        }
        while (n > 2 && (p[n - 1] == 0x00 || p[n - 1] == 0xff)) {
            --n; // padding (00 by the standard; FF from some encoders: NEMA CT2_JPLL)
        }
        lastEnds = n >= 2 && p[n - 2] == 0xff && p[n - 1] == 0xd9;
        ends += lastEnds ? 1 : 0;
    }
    if (!lastEnds || starts < static_cast<std::size_t>(frames) ||
        ends < static_cast<std::size_t>(frames)) {
        throw LoadError(where + "cut short: " + std::to_string(std::min(starts, ends)) + " of " +
                        std::to_string(frames) +
                        " frame(s) start with start-of-image and end with end-of-image");
    }
}

// GDCM's RLE codec trusts each frame's 64-byte header: a segment count or an
// offset past the fragment makes it read out of bounds (fuzz_dicom: SEGV). So
// every frame's header is checked first (PS3.5 G.5: one fragment per frame,
// one segment per byte of a sample, the first at offset 64, offsets rising
// within the fragment).
void checkRleFrames(const std::string& file, const gdcm::DataElement& pixels,
                    const PixelLayout& expected, int frames) {
    const std::string where = file + ": RLE pixel data (7FE0,0010): ";
    const gdcm::SequenceOfFragments* fragments = pixels.GetSequenceOfFragments();
    if (fragments == nullptr || fragments->GetNumberOfFragments() < std::size_t(frames)) {
        throw LoadError(where + "fewer fragments than its " + std::to_string(frames) + " frame(s)");
    }
    const std::uint32_t segments =
        static_cast<std::uint32_t>(expected.bitsAllocated / 8 * expected.samplesPerPixel);
    for (std::size_t i = 0; i < fragments->GetNumberOfFragments(); ++i) {
        const gdcm::ByteValue* bv = fragments->GetFragment(static_cast<unsigned>(i)).GetByteValue();
        const std::size_t n = bv ? static_cast<std::size_t>(bv->GetLength()) : std::size_t(0);
        const std::string frame = "frame " + std::to_string(i + 1) + ": ";
        if (n < 64) {
            throw LoadError(where + frame + "shorter than its 64-byte RLE header");
        }
        const auto* p = reinterpret_cast<const unsigned char*>(bv->GetPointer());
        const auto word = [p](std::size_t k) {
            return std::uint32_t(p[4 * k]) | std::uint32_t(p[4 * k + 1]) << 8 |
                   std::uint32_t(p[4 * k + 2]) << 16 | std::uint32_t(p[4 * k + 3]) << 24;
        };
        if (word(0) != segments) {
            throw LoadError(where + frame + "the RLE header declares " + std::to_string(word(0)) +
                            " segment(s), BitsAllocated " + std::to_string(expected.bitsAllocated) +
                            " needs " + std::to_string(segments));
        }
        for (std::uint32_t s = 0; s < segments; ++s) {
            const std::uint32_t offset = word(1 + s);
            const std::uint32_t previous = s == 0 ? 0 : word(s);
            if ((s == 0 && offset != 64) || (s > 0 && offset <= previous) || offset >= n) {
                throw LoadError(where + frame + "RLE segment " + std::to_string(s + 1) +
                                " starts at " + std::to_string(offset) +
                                ", outside its fragment or out of order");
            }
        }
    }
}

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
    if (isJpegProcess(expected.transferSyntax)) {
        checkJpegFrames(file, ds.GetDataElement(pixelData), expected, frames);
    }
    if (expected.transferSyntax == "1.2.840.10008.1.2.5") {
        checkRleFrames(file, ds.GetDataElement(pixelData), expected, frames);
    }
    // GDCM's pixel format asserts HighBit < BitsStored and aborts the process; the
    // standard asks for HighBit = BitsStored - 1 (PS3.3 C.7.6.3.1), so GDCM's codecs
    // get only that (uncompressed little endian, read directly, takes the others).
    if (expected.highBit != expected.bitsStored - 1) {
        throw LoadError(file + ": HighBit (0028,0102) " + std::to_string(expected.highBit) +
                        " is not BitsStored (0028,0101) " + std::to_string(expected.bitsStored) +
                        " - 1, which pixel data of transfer syntax " + expected.transferSyntax +
                        " needs");
    }
    gdcm::Image image;
    image.SetNumberOfDimensions(frames > 1 ? 3 : 2);
    image.SetDimension(0, static_cast<unsigned>(expected.columns));
    image.SetDimension(1, static_cast<unsigned>(expected.rows));
    if (frames > 1) {
        image.SetDimension(2, static_cast<unsigned>(frames));
    }
    image.SetPixelFormat(gdcm::PixelFormat(static_cast<unsigned short>(expected.samplesPerPixel),
                                           static_cast<unsigned short>(expected.bitsAllocated),
                                           static_cast<unsigned short>(expected.bitsStored),
                                           static_cast<unsigned short>(expected.highBit),
                                           expected.isSigned ? 1 : 0));
    // The scan accepted only interpretations GDCM knows (MONOCHROME*, PALETTE COLOR, RGB, YBR_*).
    const auto pi = gdcm::PhotometricInterpretation::GetPIType(expected.photometric.c_str());
    image.SetPhotometricInterpretation(
        gdcm::PhotometricInterpretation(pi == gdcm::PhotometricInterpretation::UNKNOWN
                                            ? gdcm::PhotometricInterpretation::MONOCHROME2
                                            : pi));
    image.SetPlanarConfiguration(static_cast<unsigned>(expected.planarConfiguration));
    image.SetTransferSyntax(parsed.GetHeader().GetDataSetTransferSyntax());
    image.SetDataElement(ds.GetDataElement(pixelData));
    return image;
}

} // namespace

DecodedFrames decodeFramesWithGdcm(const std::string& file, const PixelLayout& expected,
                                   int frames) {
    const DicomStructure structure = checkDicomStructure(file);
    if (!structure.ok) {
        throw LoadError(file + ": corrupt DICOM file: " + structure.problem);
    }
    if (const std::string truncated = truncatedPixelData(structure); !truncated.empty()) {
        throw LoadError(file + ": " + truncated);
    }
    DataSetStream stream(file, structure);
    gdcm::Reader reader;
    reader.SetStream(stream);
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
    // A codec may have changed the samples (JPEG: YBR_FULL_422 to YBR_FULL or RGB;
    // JPEG 2000: YBR_RCT/ICT to RGB); the image says what they are now.
    const char* pi = gdcm::PhotometricInterpretation::GetPIString(
        image.GetPhotometricInterpretation().GetType());
    out.photometric = pi != nullptr ? trimmedPhotometric(pi) : expected.photometric;
    out.planarConfiguration = static_cast<int>(image.GetPlanarConfiguration());
    out.frameBytes = static_cast<std::size_t>(expected.rows) * expected.columns *
                     static_cast<std::size_t>(out.format.bitsAllocated / 8) *
                     static_cast<std::size_t>(expected.samplesPerPixel);
    // GDCM leaves a JPEG's YBR_FULL_422 as the image's interpretation, but libjpeg has
    // upsampled the chrominance: a buffer of whole frames holds YBR_FULL. Only
    // uncompressed (big endian) data is still subsampled.
    if (out.photometric == "YBR_FULL_422" && expected.samplesPerPixel == 3) {
        if (out.buffer.size() >= out.frameBytes * static_cast<std::size_t>(frames)) {
            out.photometric = "YBR_FULL";
        } else {
            out.frameBytes = out.frameBytes * 2 / 3;
        }
    }
    return out;
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
