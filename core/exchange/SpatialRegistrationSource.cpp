#include "core/exchange/SpatialRegistrationSource.h"

#include <set>
#include <stdexcept>

#include "core/exchange/InstanceFiles.h"

namespace lucent {

RegisteredSeries registeredSeriesOf(const SeriesEntry& entry) {
    if (entry.format != SourceFormat::Dicom) {
        throw std::runtime_error(entry.seriesUid + ": not DICOM, so no Spatial Registration");
    }
    RegisteredSeries s{entry.studyUid, entry.seriesUid, entry.frameOfReferenceUid, {}};
    std::set<std::string> files;
    for (const SliceRef& slice : entry.slices) {
        if (files.insert(slice.file).second) {
            const InstanceHeader h = readInstanceHeader(slice.file);
            s.instances.push_back({h.sopClassUid, h.sopInstanceUid});
        }
    }
    return s;
}

SpatialRegistrationInput spatialRegistrationInput(const SeriesEntry& fixed,
                                                  const SeriesEntry& moving,
                                                  const glm::dmat4& fixedToMoving) {
    SpatialRegistrationInput in;
    in.fixed = registeredSeriesOf(fixed);
    in.moving = registeredSeriesOf(moving);
    in.patientName = fixed.patientName;
    in.patientId = fixed.patientId;
    in.studyUid = fixed.studyUid;
    in.studyDate = fixed.studyDate;
    in.studyTime = fixed.studyTime;
    in.fixedToMoving = fixedToMoving;
    return in;
}

} // namespace lucent
