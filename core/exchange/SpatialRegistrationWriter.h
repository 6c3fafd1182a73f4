#pragma once
// A registration written as a DICOM Spatial Registration object (PS3.3 A.39,
// C.20.2 Spatial Registration Module), so a PACS or another workstation can
// apply it. DCMTK stays inside the .cpp.
//
// The object lives in the fixed (registered-to) series' Frame of Reference and
// study. Its Registration Sequence has two items: the fixed Frame of Reference
// with the identity, and the moving one with inverse(fixedToMoving), the matrix
// that takes moving LPS mm into fixed LPS mm (see the .cpp for the PS3.3 wording).

#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace lucent {

struct ReferencedInstance {
    std::string sopClassUid;
    std::string sopInstanceUid;
};

// One registered series: its study, series, Frame of Reference and instances.
struct RegisteredSeries {
    std::string studyUid; // empty: the registration's own study
    std::string seriesUid;
    std::string frameOfReferenceUid;
    std::vector<ReferencedInstance> instances;
};

struct SpatialRegistrationInput {
    // Patient and study of the registration: the fixed series' (DICOM formats: DA YYYYMMDD, TM).
    std::string patientName;
    std::string patientId;
    std::string patientBirthDate;
    std::string patientSex;
    std::string studyUid;
    std::string studyDate;
    std::string studyTime;
    std::string studyId;
    std::string accessionNumber;

    RegisteredSeries fixed;
    RegisteredSeries moving;
    // Maps a point in the fixed series' LPS mm to the same anatomy in the moving
    // series' LPS mm (RegistrationResult::fixedToMoving). glm is column-major:
    // fixedToMoving[column][row].
    glm::dmat4 fixedToMoving{1.0};

    std::string seriesDescription = "Lucent registration";
    int seriesNumber = 999;
    std::string contentDescription; // e.g. the metric and iterations; may be empty
};

struct SpatialRegistrationIds {
    std::string seriesUid;
    std::string sopInstanceUid;
};

// Writes `in` to `out` (explicit VR little endian, with a file meta header) with
// new series and SOP instance UIDs, which it returns. Throws std::runtime_error
// naming the file and the cause on failure (missing UIDs, a matrix that cannot be
// inverted, a write error).
SpatialRegistrationIds writeSpatialRegistration(const std::filesystem::path& out,
                                                const SpatialRegistrationInput& in);

} // namespace lucent
