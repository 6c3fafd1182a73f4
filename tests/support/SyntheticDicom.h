#pragma once
// Writes DICOM series for tests with DCMTK (a different implementation from
// the GDCM reader under test), with voxel values given by a known function.

#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace lucent::test {

enum class Encoding {
    ExplicitLittle,
    ImplicitLittle,
    ExplicitBig,
    Deflated,
    JpegBaseline, // 8-bit lossy
    JpegLossless, // process 14 SV1
    Rle,
};

struct SyntheticSeries {
    std::string seriesUid = "1.2.826.0.1.3680043.2.1125.1";
    std::string studyUid = "1.2.826.0.1.3680043.2.1125.2";
    std::string modality = "CT";
    std::string imageType = "ORIGINAL\\PRIMARY\\AXIAL";
    std::string description = "synthetic";
    std::string patientName = "Test^Synthetic";
    std::string patientId = "SYN001";
    std::string studyDate = "20260101";
    std::string accessionNumber;
    int seriesNumber = 3;
    int columns = 8;
    int rows = 6;
    glm::dvec3 rowDir{1, 0, 0};
    glm::dvec3 colDir{0, 1, 0};
    glm::dvec2 pixelSpacing{0.5, 0.75}; // along i, along j
    double slope = 1.0;
    double intercept = -1024.0;
    int bitsAllocated = 16;
    int bitsStored = 12;
    bool isSigned = false;
    Encoding encoding = Encoding::ExplicitLittle;
    // Stored value at pixel (i, j) of the image with this index (before rescale).
    std::function<int(int i, int j, int image)> stored = [](int i, int j, int image) {
        return (i * 7 + j * 13 + image * 101) % 4000;
    };
    // Without ImagePositionPatient and ImageOrientationPatient (e.g. secondary captures).
    bool withGeometry = true;
    // Bits above BitsStored filled with ones (as some scanners store overlays there).
    bool dirtyHighBits = false;
};

// Writes one image; returns its path. position is ImagePositionPatient.
std::string writeImage(const std::string& path, const SyntheticSeries& s, int image,
                       const glm::dvec3& position, int instanceNumber);

// Writes images at the given positions as <dir>/<prefix><n>.dcm, image n at positions[n].
std::vector<std::string> writeSeries(const std::string& dir, const SyntheticSeries& s,
                                     const std::vector<glm::dvec3>& positions,
                                     const std::string& prefix = "img");

// A file with the header of an image but no Pixel Data element.
void writeWithoutPixelData(const std::string& path, const SyntheticSeries& s);

// A DICOMDIR in root listing files given relative to root (DICOM file IDs:
// upper case, at most 8 characters a component). Returns its path.
std::string writeDicomdir(const std::string& root, const std::vector<std::string>& relativeFiles);

// HU at pixel (i, j) of image n, as the series defines it.
double expectedValue(const SyntheticSeries& s, int i, int j, int image);

} // namespace lucent::test
