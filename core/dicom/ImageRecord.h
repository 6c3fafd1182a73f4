#pragma once

#include <string>
#include <vector>

#include "core/io/SeriesEntry.h"

namespace lucent {

// The header facts of one 2D image (a file, or one frame of a multi-frame
// object) that grouping, sorting and decoding need. Private to lucent_io.
struct ImageRecord : SeriesInfo {
    std::string file;
    int frame = 0;
    int frameCount = 1;
    bool enhanced = false; // per-frame functional groups (Enhanced CT/MR)
    bool cine = false;     // a frame of a multi-frame object without slice positions

    std::string sopClassUid;
    std::string sopInstanceUid;
    std::string imageType; // ImageType, or FrameType for enhanced frames
    bool localizer = false;
    int seriesNumber = 0;
    std::string studyDescription, studyTime, bodyPart;
    int instanceNumber = 0;

    bool hasPosition = false;
    glm::dvec3 position{0.0};
    glm::dvec3 rowDir{1.0, 0.0, 0.0}; // direction of increasing column index (i)
    glm::dvec3 colDir{0.0, 1.0, 0.0}; // direction of increasing row index (j)
    bool hasPixelSpacing = false;
    glm::dvec2 pixelSpacing{1.0}; // x: along i (between columns), y: along j (between rows)
    double sliceThickness = 0.0;
    double slope = 1.0;
    double intercept = 0.0;

    // What was untidy in the file but read (padding, a wrong group length, an
    // unexpected encoding, a fallback for a missing element), in words.
    std::vector<std::string> warnings;

    int samplesPerPixel = 1;
    PixelLayout pixels;
    std::uint64_t pixelOffset = 0; // see SliceRef::pixelOffset
};

struct FileScan {
    std::vector<ImageRecord> images; // empty when skipped
    std::string skipReason;          // why the file holds nothing loadable
};

// Reads the header of one file (never its pixels). Never throws.
FileScan scanDicomFile(const std::string& file);

// True when the file is a DICOMDIR (Media Storage Directory).
bool isDicomdir(const std::string& file);
// The image files a DICOMDIR references, as paths. Throws LoadError.
std::vector<std::string> dicomdirReferences(const std::string& dicomdir);

} // namespace lucent
