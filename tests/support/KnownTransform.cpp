#include "tests/support/KnownTransform.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>

namespace lucent::test {

namespace {

// Trilinear sample at a continuous index; `outside` beyond the voxel centres.
double trilinear(const Volume& v, const glm::dvec3& ijk, double outside) {
    const glm::ivec3 d = v.dims();
    if (ijk.x < 0 || ijk.y < 0 || ijk.z < 0 || ijk.x > d.x - 1 || ijk.y > d.y - 1 ||
        ijk.z > d.z - 1) {
        return outside;
    }
    const glm::ivec3 i0 = glm::min(glm::ivec3(glm::floor(ijk)), glm::max(d - 2, glm::ivec3(0)));
    const glm::dvec3 f = ijk - glm::dvec3(i0);
    double sum = 0.0;
    for (int n = 0; n < 8; ++n) {
        const glm::ivec3 o(n & 1, (n >> 1) & 1, (n >> 2) & 1);
        const double w = (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
        if (w != 0.0) {
            sum += w * v.value(i0.x + o.x, i0.y + o.y, i0.z + o.z);
        }
    }
    return sum;
}

} // namespace

glm::dmat4 rigidAbout(const glm::dvec3& c, const glm::dvec3& degrees, const glm::dvec3& t) {
    glm::dmat4 r(1.0);
    r = glm::rotate(r, glm::radians(degrees.z), glm::dvec3(0, 0, 1));
    r = glm::rotate(r, glm::radians(degrees.y), glm::dvec3(0, 1, 0));
    r = glm::rotate(r, glm::radians(degrees.x), glm::dvec3(1, 0, 0));
    return glm::translate(glm::dmat4(1.0), c + t) * r * glm::translate(glm::dmat4(1.0), -c);
}

glm::dmat4 affineAbout(const glm::dvec3& c, const glm::dvec3& scale, double shearXY,
                       double degreesZ, const glm::dvec3& t) {
    glm::dmat4 shear(1.0);
    shear[1][0] = shearXY; // column y, row x: x += shearXY * y
    const glm::dmat4 a = glm::rotate(glm::dmat4(1.0), glm::radians(degreesZ), glm::dvec3(0, 0, 1)) *
                         shear * glm::scale(glm::dmat4(1.0), scale);
    return glm::translate(glm::dmat4(1.0), c + t) * a * glm::translate(glm::dmat4(1.0), -c);
}

Volume resampled(const Volume& fixed, const glm::dmat4& fixedToMoving,
                 const std::function<double(double)>& map, const std::string& modality,
                 const std::string& frameOfReferenceUid) {
    Volume moving(fixed.geometry(), VoxelType::Float32);
    moving.modality = modality;
    moving.frameOfReferenceUid = frameOfReferenceUid;
    const glm::dmat4 indexToFixedIndex = fixed.geometry().patientToIndex() *
                                         glm::inverse(fixedToMoving) *
                                         fixed.geometry().indexToPatient();
    const glm::ivec3 d = fixed.dims();
    std::span<float> out = moving.voxels<float>();
    const auto slab = [&](int k0, int k1) {
        for (int k = k0; k < k1; ++k) {
            for (int j = 0; j < d.y; ++j) {
                for (int i = 0; i < d.x; ++i) {
                    const glm::dvec3 src = glm::dvec3(indexToFixedIndex * glm::dvec4(i, j, k, 1.0));
                    out[moving.linearIndex(i, j, k)] =
                        static_cast<float>(map(trilinear(fixed, src, -1024.0)));
                }
            }
        }
    };
    // Both halves at once: the tests' time goes to the registration, not to this.
    std::jthread other(slab, d.z / 2, d.z);
    slab(0, d.z / 2);
    return moving;
}

double mrLike(double hu) {
    return 1000.0 * std::exp(-std::pow((hu + 100.0) / 150.0, 2)) +
           500.0 * std::exp(-std::pow((hu - 40.0) / 80.0, 2)) + 20.0;
}

std::vector<glm::dvec3> bodyGrid(const Volume& fixed) {
    std::vector<glm::dvec3> points;
    const VolumeGeometry& g = fixed.geometry();
    const glm::dvec3 step = glm::dvec3(10.0) / g.spacing;
    for (double k = 2; k <= g.dims.z - 3; k += step.z) {
        for (double j = 0; j < g.dims.y; j += step.y) {
            for (double i = 0; i < g.dims.x; i += step.x) {
                const glm::ivec3 n = glm::ivec3(glm::round(glm::dvec3(i, j, k)));
                if (fixed.value(n.x, n.y, n.z) > -500.0) {
                    points.push_back(g.toPatient(glm::dvec3(n)));
                }
            }
        }
    }
    return points;
}

Tre treOf(const std::vector<glm::dvec3>& points, const glm::dmat4& truth, const glm::dmat4& found) {
    Tre t;
    for (const glm::dvec3& p : points) {
        const double e = glm::length(glm::dvec3(truth * glm::dvec4(p, 1.0)) -
                                     glm::dvec3(found * glm::dvec4(p, 1.0)));
        t.mean += e / static_cast<double>(points.size());
        t.max = std::max(t.max, e);
    }
    return t;
}

} // namespace lucent::test
