#pragma once

#include <string>
#include <vector>

#include "core/volume/Volume.h"

namespace lucent {

// What an entry of a catalog is: a stack that makes a volume, a scout, a lone image, or
// 2D frames that make no volume (colour images, multi-frame cine): loadStack, not loadSeries.
enum class SeriesKind { Volume, Localizer, Image, Stack };
const char* seriesKindName(SeriesKind kind);

enum class SourceFormat { Dicom, MetaImage, Nifti, InVesalius };

// One 2D image of a DICOM series: a file, and a frame in it for multi-frame objects.
struct SliceRef {
    std::string file;
    int frame = 0;
    glm::dvec3 position{0.0}; // ImagePositionPatient of its first pixel, LPS mm
    double slope = 1.0;
    double intercept = 0.0;
    // Byte offset of uncompressed little-endian pixel data in the file, read
    // directly; 0 when the frame must be decoded through GDCM.
    std::uint64_t pixelOffset = 0;
};

// How the stored pixels of a DICOM entry look before rescale.
struct PixelLayout {
    int rows = 0;
    int columns = 0;
    int bitsAllocated = 16;
    int bitsStored = 16;
    int highBit = 15;
    bool isSigned = false;
    std::string transferSyntax;              // UID
    int samplesPerPixel = 1;                 // 3 for colour
    int planarConfiguration = 0;             // colour: 0 RGBRGB..., 1 RR..GG..BB..
    std::string photometric = "MONOCHROME2"; // PhotometricInterpretation (0028,0004)
};

// Something a path holds that can be loaded as a volume. The geometry is the
// one the loaded volume will have (after any regularisation the warnings describe).
struct SeriesEntry : SeriesInfo {
    std::string id; // unique in its catalog: the series UID, or UID#n for further parts
    SeriesKind kind = SeriesKind::Volume;
    SourceFormat format = SourceFormat::Dicom;
    VolumeGeometry geometry;
    VoxelType voxelType = VoxelType::Int16;
    std::vector<std::string> warnings;
    // DICOM only: of the first image (hanging protocols match on them).
    int seriesNumber = 0;
    double sliceThickness = 0.0; // mm, 0 when absent
    std::string studyDescription;
    std::string studyTime; // DICOM TM text (0008,0030)
    std::string bodyPart;  // BodyPartExamined (0018,0015)

    // DICOM only: the images, sorted ascending along the slice normal.
    std::vector<SliceRef> slices;
    PixelLayout pixels;
    // DICOM only: true when the images are resampled onto geometry (tilt, uneven gaps).
    bool resampled = false;
    // DICOM only: whether the images carry a patient position and orientation, and a
    // pixel spacing (without them the geometry is the image grid at 1 mm).
    bool hasPosition = true;
    bool hasPixelSpacing = true;

    // Other formats: the file to read.
    std::string file;
};

} // namespace lucent
