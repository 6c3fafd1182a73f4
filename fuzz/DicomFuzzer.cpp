// fuzz_dicom: one input is one DICOM file. It goes the way a file of a study
// goes: the structural walk (DicomStructure.h) and the header scan and series
// grouping of that one file (SeriesScanner.h), a DICOMDIR's references, then the frames
// of each entry it yields (a volume, or a 2D stack: colour, palette, cine) are decoded
// (FrameDecoder.h: native reads, GDCM's codecs; not JPEG-LS, which a child process decodes),
// rescaled and resampled. Bad input must end in a skip reason or a LoadError; anything else (a
// crash, an assertion, another exception, UB, a leak) is a finding.
#include <cstddef>
#include <cstdint>

#include "core/dicom/FrameDecoder.h"
#include "core/dicom/ImageRecord.h"
#include "core/dicom/SeriesScanner.h"
#include "core/dicom/StackLoader.h"
#include "core/io/Catalog.h"
#include "fuzz/ScratchFile.h"

namespace {

// Entries larger than this are scanned but not decoded: decoding big frames
// tests codecs more slowly, not the parsing around them.
constexpr std::uint64_t kMaxDecodedVoxels = 512 * 512;

std::uint64_t voxelsOf(const lucent::SeriesEntry& entry) {
    return static_cast<std::uint64_t>(entry.pixels.rows) *
           static_cast<std::uint64_t>(entry.pixels.columns) * entry.slices.size();
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static lucent::fuzz::ScratchFile file("input.dcm");
    const std::string& path = file.write(data, size);

    // scanDicomFile walks the structure before GDCM sees the file.
    lucent::LoadControl control;
    control.threads = 1;
    lucent::Catalog catalog;
    lucent::scanDicomFiles({path}, catalog, control);
    for (const lucent::SkippedFile& skipped : catalog.skipped) {
        if (skipped.reason.starts_with("DICOMDIR") && lucent::isDicomdir(path)) {
            try {
                (void)lucent::dicomdirReferences(path);
            } catch (const lucent::LoadError&) {
            }
        }
    }
    for (const lucent::SeriesEntry& entry : catalog.series) {
        // JPEG-LS is decoded by dcmdjpls in a child process (JpegLsDecoder.cpp):
        // outside this process's sanitizers, and a second per input.
        if (voxelsOf(entry) > kMaxDecodedVoxels || lucent::isJpegLs(entry.pixels.transferSyntax)) {
            continue;
        }
        try {
            // 2D stacks (colour, palette, cine) decode through loadStack.
            if (entry.kind == lucent::SeriesKind::Stack) {
                (void)lucent::loadStack(entry, control);
            } else {
                (void)lucent::loadSeries(entry, control);
            }
        } catch (const lucent::LoadError&) {
        }
    }
    return 0;
}
