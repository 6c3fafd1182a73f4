#pragma once
// A second study of the same patient made from real DICOM files with DCMTK: what a
// follow-up read compares against (a prior), for tests of linking, hanging and
// priors.

#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace lucent::test {

struct PriorStudy {
    std::string studyUid;
    std::string seriesUid;
    std::string frameOfReferenceUid;
    std::vector<std::filesystem::path> files;
};

// Copies every DICOM file directly in `source` into `target` (created) with new
// study, series and SOP instance UIDs and `studyDate`. With a non-zero `shift` the
// copy also gets a new Frame of Reference and every ImagePositionPatient moved by
// `shift` (LPS mm): the same anatomy `shift` away, as another scanner would place it.
// Throws std::runtime_error naming the file on failure.
PriorStudy writePriorStudy(const std::filesystem::path& source, const std::filesystem::path& target,
                           const std::string& studyDate, const glm::dvec3& shift = glm::dvec3(0.0));

} // namespace lucent::test
