#pragma once
// A DICOM Spatial Registration object read back (Lucent's or another program's): the
// Frames of Reference it relates, each with the matrix that takes its LPS mm into the
// object's own Frame of Reference (PS3.3 C.20.2). DCMTK stays inside the .cpp.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace lucent {

struct FrameRegistration {
    std::string frameOfReferenceUid;
    glm::dmat4 toRegistered{1.0}; // this frame's LPS mm -> the object's frame's LPS mm
};

struct SpatialRegistration {
    std::string sopInstanceUid;
    std::string frameOfReferenceUid; // the registered-to frame
    std::vector<FrameRegistration> frames;
};

// Throws std::runtime_error naming the file and the element for what it cannot use: not a
// Spatial Registration, no Registration Sequence, a matrix that is not 16 numbers or whose
// last row is not 0 0 0 1, a singular matrix.
SpatialRegistration readSpatialRegistration(const std::filesystem::path& file);

// Maps `from` frame's LPS mm to `to` frame's (inverse(M_to) * M_from); nullopt when the
// object relates not both frames. The same frame gives the identity.
std::optional<glm::dmat4> frameTransform(const SpatialRegistration& registration,
                                         const std::string& from, const std::string& to);

} // namespace lucent
