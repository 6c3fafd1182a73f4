#include "core/hanging/HangingSeries.h"
#include "core/hanging/HangingProtocolNames_p.h"

#include <cmath>
#include <numbers>

namespace lucent {

SliceOrientation sliceOrientationOf(const glm::dvec3& rowDir, const glm::dvec3& colDir) {
    const glm::dvec3 cross = glm::cross(rowDir, colDir);
    const double length = glm::length(cross);
    if (!(length > 0.0)) {
        return SliceOrientation::Oblique;
    }
    const glm::dvec3 normal = glm::abs(cross / length);
    // LPS: x runs left-right (sagittal normal), y front-back (coronal), z foot-head (axial).
    int axis = 0;
    for (int a = 1; a < 3; ++a) {
        if (normal[a] > normal[axis]) {
            axis = a;
        }
    }
    if (normal[axis] < std::cos(kObliqueDegrees * std::numbers::pi / 180.0)) {
        return SliceOrientation::Oblique;
    }
    constexpr SliceOrientation kByAxis[] = {SliceOrientation::Sagittal, SliceOrientation::Coronal,
                                            SliceOrientation::Axial};
    return kByAxis[axis];
}

const char* sliceOrientationName(SliceOrientation orientation) {
    return nameOf(orientation, kOrientationNames).data();
}

HangingSeries hangingSeriesOf(const SeriesEntry& entry, const std::string& path) {
    HangingSeries s;
    s.seriesUid = entry.seriesUid;
    s.studyUid = entry.studyUid;
    s.patientId = entry.patientId;
    s.studyDate = entry.studyDate;
    s.studyTime = entry.studyTime;
    s.studyDescription = entry.studyDescription;
    s.modality = entry.modality;
    s.bodyPart = entry.bodyPart;
    s.description = entry.description;
    s.seriesNumber = entry.seriesNumber;
    s.sliceThickness = entry.sliceThickness;
    // The geometry's i and j axes are the images' row and column directions.
    const glm::dmat3& d = entry.geometry.direction;
    s.orientation = sliceOrientationOf(d[0], d[1]);
    s.instances =
        entry.slices.empty() ? entry.geometry.dims.z : static_cast<int>(entry.slices.size());
    s.kind = entry.kind;
    s.path = path;
    s.id = entry.id;
    return s;
}

} // namespace lucent
