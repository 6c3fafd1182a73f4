#include "core/segdicom/SegmentationDicomItems_p.h"

#include <algorithm>
#include <mutex>

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcrledrg.h>
#include <dcmtk/dcmdata/dcxfer.h>

#include "core/report/MeasurementReport.h" // kLucentManufacturer

namespace lucent::segdicom {

namespace fs = std::filesystem;

DcmItem* item(DcmItem& d, const DcmTagKey& sequence) {
    DcmItem* found = nullptr;
    return d.findAndGetSequenceItem(sequence, found, 0).good() ? found : nullptr;
}

std::vector<DcmItem*> items(DcmItem& d, const DcmTagKey& sequence) {
    std::vector<DcmItem*> out;
    DcmSequenceOfItems* seq = nullptr;
    if (d.findAndGetSequence(sequence, seq).bad() || seq == nullptr) {
        return out;
    }
    out.reserve(seq->card());
    for (DcmObject* o = seq->nextInContainer(nullptr); o != nullptr; o = seq->nextInContainer(o)) {
        out.push_back(static_cast<DcmItem*>(o));
    }
    return out;
}

CodedConcept codeOf(DcmItem& d, const DcmTagKey& sequence) {
    CodedConcept c;
    DcmItem* code = item(d, sequence);
    if (code == nullptr) {
        return c;
    }
    c.value = text(*code, DCM_CodeValue);
    if (c.value.empty()) {
        c.value = text(*code, DCM_LongCodeValue);
    }
    if (c.value.empty()) {
        c.value = text(*code, DCM_URNCodeValue);
    }
    c.scheme = text(*code, DCM_CodingSchemeDesignator);
    c.meaning = text(*code, DCM_CodeMeaning);
    return c;
}

void loadSegmentation(DcmFileFormat& format, const fs::path& file, bool pixels) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) {
        throw SegmentationDicomError(file.string() + ": no such file");
    }
    const OFCondition c = format.loadFile(file.c_str(), EXS_Unknown, EGL_noChange,
                                          pixels ? DCM_MaxReadLength : 4096, ERM_autoDetect);
    if (c.bad()) {
        throw SegmentationDicomError(file.string() + ": not a readable DICOM file (" + c.text() +
                                     "; truncated or not DICOM)");
    }
    const std::string sopClass = text(*format.getDataset(), DCM_SOPClassUID);
    if (sopClass != kSegmentationSopClassUid) {
        throw SegmentationDicomError(file.string() + ": not a DICOM Segmentation (SOP class " +
                                     (sopClass.empty() ? std::string("missing") : sopClass) + ")");
    }
}

SegmentationDicomHeader headerOf(DcmDataset& d, const fs::path& file) {
    SegmentationDicomHeader h;
    h.sopInstanceUid = text(d, DCM_SOPInstanceUID);
    h.seriesUid = text(d, DCM_SeriesInstanceUID);
    h.studyUid = text(d, DCM_StudyInstanceUID);
    h.frameOfReferenceUid = text(d, DCM_FrameOfReferenceUID);
    h.manufacturer = text(d, DCM_Manufacturer);
    h.seriesDescription = text(d, DCM_SeriesDescription);
    h.writtenByLucent = h.manufacturer == kLucentManufacturer;
    if (h.sopInstanceUid.empty() || h.seriesUid.empty()) {
        throw SegmentationDicomError(file.string() + ": lacks its SOP Instance or Series UID");
    }
    const auto addSeries = [&](DcmItem& holder) {
        for (DcmItem* s : items(holder, DCM_ReferencedSeriesSequence)) {
            h.referencedSeries.push_back(text(*s, DCM_SeriesInstanceUID));
            for (DcmItem* i : items(*s, DCM_ReferencedInstanceSequence)) {
                h.referencedInstances.push_back(text(*i, DCM_ReferencedSOPInstanceUID));
            }
        }
    };
    addSeries(d);
    for (DcmItem* study : items(d, DCM_StudiesContainingOtherReferencedInstancesSequence)) {
        addSeries(*study);
    }
    for (DcmItem* frame : items(d, DCM_PerFrameFunctionalGroupsSequence)) {
        for (DcmItem* derivation : items(*frame, DCM_DerivationImageSequence)) {
            for (DcmItem* source : items(*derivation, DCM_SourceImageSequence)) {
                h.referencedInstances.push_back(text(*source, DCM_ReferencedSOPInstanceUID));
            }
        }
    }
    std::sort(h.referencedInstances.begin(), h.referencedInstances.end());
    h.referencedInstances.erase(
        std::unique(h.referencedInstances.begin(), h.referencedInstances.end()),
        h.referencedInstances.end());
    return h;
}

PixelFrames pixelFramesOf(DcmDataset& d, const fs::path& file) {
    PixelFrames f;
    Uint16 rows = 0, columns = 0, bits = 0;
    Sint32 frames = 1;
    d.findAndGetUint16(DCM_Rows, rows);
    d.findAndGetUint16(DCM_Columns, columns);
    d.findAndGetUint16(DCM_BitsAllocated, bits);
    if (d.tagExists(DCM_NumberOfFrames) && d.findAndGetSint32(DCM_NumberOfFrames, frames).bad()) {
        frames = 0;
    }
    const std::string type = text(d, DCM_SegmentationType);
    if (rows == 0 || columns == 0 || frames <= 0) {
        throw SegmentationDicomError(file.string() + ": no Rows, Columns or Number of Frames");
    }
    f.rows = rows;
    f.columns = columns;
    f.frames = static_cast<std::size_t>(frames);
    f.fractional = type == "FRACTIONAL";
    if (type != "BINARY" && !f.fractional) {
        throw SegmentationDicomError(file.string() + ": Segmentation Type '" + type +
                                     "' (Lucent reads BINARY and FRACTIONAL)");
    }
    if (bits != (f.fractional ? 8 : 1)) {
        throw SegmentationDicomError(file.string() + ": " + type + " with Bits Allocated " +
                                     std::to_string(bits));
    }
    Uint16 maximum = 255;
    d.findAndGetUint16(DCM_MaximumFractionalValue, maximum);
    f.threshold = (std::max<unsigned>(maximum, 1) + 1) / 2;
    if (DcmXfer(d.getOriginalXfer()).isEncapsulated()) {
        static std::once_flag rle; // DCMTK's own codec, registered once for every thread
        std::call_once(rle, [] { DcmRLEDecoderRegistration::registerCodecs(); });
        if (d.chooseRepresentation(EXS_LittleEndianExplicit, nullptr).bad()) {
            throw SegmentationDicomError(file.string() + ": compressed pixel data (" +
                                         DcmXfer(d.getOriginalXfer()).getXferName() +
                                         ") Lucent cannot decode");
        }
    }
    DcmElement* pixelData = nullptr;
    const Uint8* data = nullptr;
    if (d.findAndGetElement(DCM_PixelData, pixelData).bad() || pixelData == nullptr) {
        throw SegmentationDicomError(file.string() + ": no Pixel Data");
    }
    Uint8* bytes = nullptr;
    if (pixelData->getUint8Array(bytes).bad() || bytes == nullptr) {
        throw SegmentationDicomError(file.string() + ": unreadable Pixel Data");
    }
    data = bytes;
    const std::size_t pixels = static_cast<std::size_t>(rows) * columns * f.frames;
    const std::size_t needed = f.fractional ? pixels : (pixels + 7) / 8;
    if (pixelData->getLength() < needed) {
        throw SegmentationDicomError(file.string() + ": Pixel Data holds " +
                                     std::to_string(pixelData->getLength()) + " bytes, its " +
                                     std::to_string(f.frames) + " frames need " +
                                     std::to_string(needed) + " (truncated?)");
    }
    f.data = data;
    if (f.fractional && f.threshold > 1 &&
        std::all_of(data, data + needed, [](Uint8 v) { return v <= 1; })) {
        f.threshold = 1;
        f.binaryAsFractional = true;
    }
    return f;
}

void PixelFrames::addFrame(std::size_t n, SegmentMask& mask, int k) const {
    const std::size_t plane = static_cast<std::size_t>(rows) * columns;
    const std::size_t first = n * plane;
    const std::size_t base = plane * static_cast<std::size_t>(k);
    if (fractional) {
        for (std::size_t p = 0; p < plane; ++p) {
            if (data[first + p] >= threshold) {
                mask.set(base + p);
            }
        }
        return;
    }
    for (std::size_t p = 0; p < plane;) {
        const std::size_t bit = first + p;
        if ((bit & 7) == 0 && p + 8 <= plane && data[bit >> 3] == 0) {
            p += 8; // a whole empty byte
            continue;
        }
        if ((data[bit >> 3] >> (bit & 7)) & 1u) {
            mask.set(base + p);
        }
        ++p;
    }
}

} // namespace lucent::segdicom
