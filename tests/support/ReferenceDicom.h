#pragma once
// Reads one uncompressed DICOM image with DCMTK, for tests that check the
// loader's voxels and geometry against the files themselves.

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace lucent::test {

struct ReferenceImage {
    std::string file;
    glm::dvec3 position{0.0};
    glm::dvec3 rowDir{1, 0, 0};
    glm::dvec3 colDir{0, 1, 0};
    glm::dvec2 spacing{1.0}; // along i, along j
    int columns = 0;
    int rows = 0;
    std::vector<double> values; // rescaled, i fastest

    double at(int i, int j) const { return values[i + std::size_t(columns) * j]; }
    // Bilinear value at a patient point in this image's plane; false when outside.
    bool sample(const glm::dvec3& lps, double& value, double& distanceFromPlane) const;
};

// detectEncoding: the data set's encoding is found from its bytes, as dcmdump's
// --read-xfer-detect (-td) does, not taken from the file meta information.
// Without PixelSpacing the spacing is ImagerPixelSpacing's, if present.
ReferenceImage readReferenceImage(const std::string& file, bool detectEncoding = false);

} // namespace lucent::test
