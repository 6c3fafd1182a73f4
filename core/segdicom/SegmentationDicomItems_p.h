#pragma once
// Internal to core/segdicom: reading the parts of a SEG dataset with dcmdata.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include "core/report/DicomItemValues.h"
#include "core/segdicom/SegmentationDicom.h"

namespace lucent::segdicom {

using dicomitem::numbers;
using dicomitem::text;
// The first item of a sequence (nullptr when absent or empty), and all of them.
DcmItem* item(DcmItem& d, const DcmTagKey& sequence);
std::vector<DcmItem*> items(DcmItem& d, const DcmTagKey& sequence);
// The first code of a code sequence (value from CodeValue, LongCodeValue or URNCodeValue).
CodedConcept codeOf(DcmItem& d, const DcmTagKey& sequence);

// Loads a SEG (its pixel data too when `pixels`). Throws SegmentationDicomError naming the
// file when it is not DICOM, is cut short, or is not a Segmentation.
void loadSegmentation(DcmFileFormat& format, const std::filesystem::path& file, bool pixels);
SegmentationDicomHeader headerOf(DcmDataset& d, const std::filesystem::path& file);

// The frames of a SEG's Pixel Data, BINARY (1 bit, frames packed with no padding, the low bit
// first) or FRACTIONAL (8 bits; a pixel counts from half the maximum fractional value on, or
// from 1 when no pixel holds more: dcmjs, and so OHIF, stores binary masks as FRACTIONAL 0/1
// under RLE with a maximum of 255).
struct PixelFrames {
    int rows = 0;
    int columns = 0;
    std::size_t frames = 0;
    bool fractional = false;
    unsigned threshold = 1; // FRACTIONAL: the least value that counts
    bool binaryAsFractional = false;
    const Uint8* data = nullptr; // owned by the dataset

    // Sets the voxels of frame n on slice k of mask.
    void addFrame(std::size_t n, SegmentMask& mask, int k) const;
};

// Throws SegmentationDicomError naming the file when the pixel data is missing, shorter than
// its frames need, compressed in a way DCMTK cannot undo, or of another bit depth.
PixelFrames pixelFramesOf(DcmDataset& d, const std::filesystem::path& file);

} // namespace lucent::segdicom
