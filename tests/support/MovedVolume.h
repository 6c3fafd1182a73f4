#pragma once
// A real volume placed elsewhere by a known rigid transform, in a new Frame of Reference:
// what the fusion tests and the overlay bench resample back through that transform.

#include <cstring>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/volume/Volume.h"

namespace lucent::test {

// A rigid transform about c: rotation (degrees about x, y, z in turn), then a shift.
inline glm::dmat4 rigidAbout(const glm::dvec3& c, const glm::dvec3& degrees, const glm::dvec3& t) {
    glm::dmat4 r(1.0);
    r = glm::rotate(r, glm::radians(degrees.z), glm::dvec3(0, 0, 1));
    r = glm::rotate(r, glm::radians(degrees.y), glm::dvec3(0, 1, 0));
    r = glm::rotate(r, glm::radians(degrees.x), glm::dvec3(1, 0, 0));
    return glm::translate(glm::dmat4(1.0), c + t) * r * glm::translate(glm::dmat4(1.0), -c);
}

// The volume's voxels on a grid moved by `move`: the copy's anatomy at move(p) is the
// original's at p. Same modality, Frame of Reference 2.25.2029.
inline Volume movedCopy(const Volume& ct, const glm::dmat4& move) {
    VolumeGeometry g = ct.geometry();
    g.origin = glm::dvec3(move * glm::dvec4(g.origin, 1.0));
    g.direction = glm::dmat3(move) * g.direction;
    Volume copy(g, ct.type());
    std::memcpy(copy.bytes().data(), ct.bytes().data(), ct.byteCount());
    copy.modality = ct.modality;
    copy.frameOfReferenceUid = "2.25.2029";
    return copy;
}

} // namespace lucent::test
