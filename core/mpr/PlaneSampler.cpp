#include "core/mpr/PlaneSampler.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "core/pet/PetDisplay.h"

namespace lucent {

namespace {

// One axis of a trilinear lookup: the two neighbouring voxel indices and the weight of the second.
struct AxisWeights {
    int i0 = 0;
    int i1 = 0;
    double f = 0.0;
};

AxisWeights axisWeights(double c, int n) {
    c = std::clamp(c, 0.0, static_cast<double>(n - 1));
    AxisWeights w;
    w.i0 = static_cast<int>(c); // c >= 0, so truncation is floor
    if (w.i0 >= n - 1) {
        w.i0 = n - 1;
        w.i1 = n - 1;
        return w;
    }
    w.i1 = w.i0 + 1;
    w.f = c - w.i0;
    return w;
}

bool insideBox(const glm::dvec3& ijk, const glm::ivec3& dims) {
    for (int a = 0; a < 3; ++a) {
        // NaN fails both comparisons and counts as outside.
        if (!(ijk[a] >= -0.5 && ijk[a] <= dims[a] - 0.5)) {
            return false;
        }
    }
    return true;
}

template <class T>
double trilinear(std::span<const T> data, const glm::ivec3& dims, const glm::dvec3& ijk) {
    const AxisWeights x = axisWeights(ijk.x, dims.x);
    const AxisWeights y = axisWeights(ijk.y, dims.y);
    const AxisWeights z = axisWeights(ijk.z, dims.z);
    const std::size_t nx = static_cast<std::size_t>(dims.x);
    const std::size_t nxy = nx * static_cast<std::size_t>(dims.y);
    auto at = [&](int i, int j, int k) {
        return static_cast<double>(
            data[static_cast<std::size_t>(i) + nx * static_cast<std::size_t>(j) +
                 nxy * static_cast<std::size_t>(k)]);
    };
    auto lerp = [](double a, double b, double f) { return a + (b - a) * f; };
    const double c00 = lerp(at(x.i0, y.i0, z.i0), at(x.i1, y.i0, z.i0), x.f);
    const double c10 = lerp(at(x.i0, y.i1, z.i0), at(x.i1, y.i1, z.i0), x.f);
    const double c01 = lerp(at(x.i0, y.i0, z.i1), at(x.i1, y.i0, z.i1), x.f);
    const double c11 = lerp(at(x.i0, y.i1, z.i1), at(x.i1, y.i1, z.i1), x.f);
    return lerp(lerp(c00, c10, y.f), lerp(c01, c11, y.f), z.f);
}

template <class T>
void sampleRows(std::span<const T> data, const VolumeGeometry& g, const SlicePlane& plane,
                float fill, std::vector<float>& out) {
    const glm::dmat4 toIndex = g.patientToIndex();
    // The plane is affine in index space: one origin and one step per pixel, row and slab sample.
    const glm::dvec3 origin = glm::dvec3(toIndex * glm::dvec4(plane.pointAt(0.0, 0.0), 1.0));
    const glm::dmat3 linear(toIndex);
    const glm::dvec3 du = linear * (plane.u * plane.pixelSize);
    const glm::dvec3 dv = linear * (plane.v * plane.pixelSize);

    std::vector<glm::dvec3> slab{glm::dvec3(0.0)};
    if (plane.slabThickness > 0.0) {
        const glm::dvec3 n = glm::normalize(plane.normal());
        const double step = sliceStep(g, n);
        const int count = std::max(2, static_cast<int>(std::ceil(plane.slabThickness / step)) + 1);
        slab.clear();
        for (int s = 0; s < count; ++s) {
            const double t = -0.5 * plane.slabThickness + plane.slabThickness * s / (count - 1);
            slab.push_back(linear * (n * t));
        }
    }
    const bool thin = slab.size() == 1;
    const glm::ivec3 dims = g.dims;

#pragma omp parallel for schedule(static)
    for (int y = 0; y < plane.height; ++y) {
        float* row = out.data() + static_cast<std::size_t>(y) * plane.width;
        const glm::dvec3 rowStart = origin + dv * static_cast<double>(y);
        for (int x = 0; x < plane.width; ++x) {
            const glm::dvec3 p = rowStart + du * static_cast<double>(x);
            if (thin) {
                row[x] = insideBox(p, dims) ? static_cast<float>(trilinear(data, dims, p)) : fill;
                continue;
            }
            double acc = plane.slabMode == SlabMode::Mip     ? -HUGE_VAL
                         : plane.slabMode == SlabMode::MinIp ? HUGE_VAL
                                                             : 0.0;
            int used = 0;
            for (const glm::dvec3& offset : slab) {
                const glm::dvec3 q = p + offset;
                if (!insideBox(q, dims)) {
                    continue;
                }
                const double value = trilinear(data, dims, q);
                switch (plane.slabMode) {
                case SlabMode::Mip:
                    acc = std::max(acc, value);
                    break;
                case SlabMode::MinIp:
                    acc = std::min(acc, value);
                    break;
                case SlabMode::Average:
                    acc += value;
                    break;
                }
                ++used;
            }
            if (used == 0) {
                row[x] = fill;
            } else {
                row[x] = static_cast<float>(plane.slabMode == SlabMode::Average ? acc / used : acc);
            }
        }
    }
}

} // namespace

const char* orientationName(Orientation orientation) {
    switch (orientation) {
    case Orientation::Axial:
        return "Axial";
    case Orientation::Coronal:
        return "Coronal";
    case Orientation::Sagittal:
        return "Sagittal";
    }
    return "?";
}

glm::dvec3 SlicePlane::pointAt(double x, double y) const {
    return centre + u * ((x - 0.5 * (width - 1)) * pixelSize) +
           v * ((y - 0.5 * (height - 1)) * pixelSize);
}

glm::dvec2 SlicePlane::pixelOf(const glm::dvec3& p) const {
    const glm::dvec3 d = p - centre;
    return {glm::dot(d, u) / pixelSize + 0.5 * (width - 1),
            glm::dot(d, v) / pixelSize + 0.5 * (height - 1)};
}

double fitPixelSize(const VolumeGeometry& geometry, const glm::dvec3& u, const glm::dvec3& v,
                    int width, int height) {
    double uMin = HUGE_VAL, uMax = -HUGE_VAL, vMin = HUGE_VAL, vMax = -HUGE_VAL;
    for (int corner = 0; corner < 8; ++corner) {
        // The outer faces of the border voxels: index -0.5 and n - 0.5.
        const glm::dvec3 ijk((corner & 1) ? geometry.dims.x - 0.5 : -0.5,
                             (corner & 2) ? geometry.dims.y - 0.5 : -0.5,
                             (corner & 4) ? geometry.dims.z - 0.5 : -0.5);
        const glm::dvec3 p = geometry.toPatient(ijk);
        uMin = std::min(uMin, glm::dot(p, u));
        uMax = std::max(uMax, glm::dot(p, u));
        vMin = std::min(vMin, glm::dot(p, v));
        vMax = std::max(vMax, glm::dot(p, v));
    }
    const double minSpacing =
        std::min({geometry.spacing.x, geometry.spacing.y, geometry.spacing.z});
    if (width <= 0 || height <= 0) {
        return minSpacing;
    }
    const double size = std::max((uMax - uMin) / width, (vMax - vMin) / height);
    return size > 0.0 ? size : minSpacing;
}

SlicePlane standardPlane(const VolumeGeometry& geometry, Orientation orientation,
                         const glm::dvec3& centre, int width, int height) {
    SlicePlane plane;
    plane.centre = centre;
    switch (orientation) {
    case Orientation::Axial:
        plane.u = {1.0, 0.0, 0.0};
        plane.v = {0.0, 1.0, 0.0};
        break;
    case Orientation::Coronal:
        plane.u = {1.0, 0.0, 0.0};
        plane.v = {0.0, 0.0, -1.0};
        break;
    case Orientation::Sagittal:
        plane.u = {0.0, 1.0, 0.0};
        plane.v = {0.0, 0.0, -1.0};
        break;
    }
    plane.width = std::max(0, width);
    plane.height = std::max(0, height);
    plane.pixelSize = fitPixelSize(geometry, plane.u, plane.v, plane.width, plane.height);
    return plane;
}

double sliceStep(const VolumeGeometry& geometry, const glm::dvec3& normal) {
    const glm::dvec3 n = glm::normalize(normal);
    double best = HUGE_VAL;
    for (int a = 0; a < 3; ++a) {
        const double along = std::abs(glm::dot(n, glm::dvec3(geometry.direction[a])));
        if (along > 1e-9) {
            best = std::min(best, geometry.spacing[a] / along);
        }
    }
    return std::isfinite(best) ? best : 1.0;
}

double sampleAt(const Volume& volume, const glm::dvec3& ijk, double fill) {
    if (volume.empty() || !insideBox(ijk, volume.dims())) {
        return fill;
    }
    return visitVoxels(volume, [&](auto data) {
        return trilinear(std::span(data.data(), data.size()), volume.dims(), ijk);
    });
}

std::vector<float> sampleImage(const Volume& volume, const SlicePlane& plane, float fill) {
    const int w = std::max(0, plane.width);
    const int h = std::max(0, plane.height);
    std::vector<float> out(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), fill);
    if (volume.empty() || out.empty()) {
        return out;
    }
    visitVoxels(volume, [&](auto data) {
        sampleRows(std::span(data.data(), data.size()), volume.geometry(), plane, fill, out);
    });
    return out;
}

std::uint8_t windowToGrey(double value, double center, double width) {
    if (std::isnan(value)) {
        return 0;
    }
    const double w = std::max(width, 1e-9);
    const double g = (value - (center - 0.5 * w)) / w * 255.0;
    return static_cast<std::uint8_t>(std::clamp(std::lround(g), 0L, 255L));
}

WindowLevel defaultWindow(const Volume& volume) {
    WindowLevel window;
    if (volume.modality == "CT" || volume.empty()) {
        return window;
    }
    if (volume.pet && volume.pet->inSuv()) {
        window.width = kSuvWindowHigh - kSuvWindowLow;
        window.center = 0.5 * (kSuvWindowLow + kSuvWindowHigh);
        window.step = kSuvWindowStep;
        return window;
    }
    const std::size_t count = volume.geometry().voxelCount();
    const std::size_t stride = std::max<std::size_t>(1, count / 1'000'000);
    std::vector<float> values;
    values.reserve(count / stride + 1);
    visitVoxels(volume, [&](auto data) {
        for (std::size_t n = 0; n < data.size(); n += stride) {
            if (std::isfinite(static_cast<double>(data[n]))) {
                values.push_back(static_cast<float>(data[n]));
            }
        }
    });
    if (values.empty()) {
        return window;
    }
    auto quantile = [&values](double q) {
        const auto at = values.begin() + static_cast<std::ptrdiff_t>(q * (values.size() - 1));
        std::nth_element(values.begin(), at, values.end());
        return static_cast<double>(*at);
    };
    const double lo = quantile(0.01);
    const double hi = quantile(0.99);
    window.width = std::max(hi - lo, 1e-6);
    window.center = 0.5 * (lo + hi);
    window.step = window.width / 1000.0;
    return window;
}

std::string directionLabel(const glm::dvec3& direction) {
    struct Part {
        double magnitude;
        char letter;
    };
    std::array<Part, 3> parts{{{std::abs(direction.x), direction.x >= 0 ? 'L' : 'R'},
                               {std::abs(direction.y), direction.y >= 0 ? 'P' : 'A'},
                               {std::abs(direction.z), direction.z >= 0 ? 'S' : 'I'}}};
    std::stable_sort(parts.begin(), parts.end(),
                     [](const Part& a, const Part& b) { return a.magnitude > b.magnitude; });
    std::string label;
    if (!(parts[0].magnitude > 0.0)) {
        return label;
    }
    for (const Part& part : parts) {
        if (part.magnitude >= 0.25 * parts[0].magnitude) {
            label += part.letter;
        }
    }
    return label;
}

} // namespace lucent
