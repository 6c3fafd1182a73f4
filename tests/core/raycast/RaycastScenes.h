#pragma once
// Volumes, transfer functions and helpers shared by the ray-caster test suites.

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "core/image/Image.h"
#include "core/scene/RenderDescription.h"

namespace lucent::test {

inline Volume makeVolume(glm::ivec3 dims, const std::function<double(int, int, int)>& f,
                         VoxelType type = VoxelType::Float32) {
    VolumeGeometry g;
    g.dims = dims;
    Volume v(g, type);
    visitVoxels(v, [&](auto out) {
        using T = typename decltype(out)::element_type;
        for (int k = 0; k < dims.z; ++k) {
            for (int j = 0; j < dims.y; ++j) {
                for (int i = 0; i < dims.x; ++i) {
                    out[v.linearIndex(i, j, k)] = static_cast<T>(f(i, j, k));
                }
            }
        }
    });
    v.modality = "CT";
    return v;
}

inline TransferFunction flatTf(double opacity, bool shading = false) {
    TransferFunction tf;
    tf.name = "flat";
    tf.opacity = {{-10000.0, opacity}, {10000.0, opacity}};
    tf.colour = {{-10000.0, {1, 1, 1}}, {10000.0, {1, 1, 1}}};
    tf.shading.enabled = shading;
    return tf;
}

// Transparent below 50, opacity ramping to 0.3 at 150; colour by value.
inline TransferFunction rampTf(bool shading) {
    TransferFunction tf;
    tf.name = "ramp";
    tf.opacity = {{50.0, 0.0}, {150.0, 0.3}};
    tf.colour = {{0.0, {1.0, 0.5, 0.2}}, {200.0, {0.9, 0.9, 1.0}}};
    tf.shading.enabled = shading;
    return tf;
}

inline RenderDescription describe(const Volume& v, TransferFunction tf, int size = 33) {
    RenderDescription d;
    d.volume = &v;
    d.transferFunction = std::move(tf);
    d.width = d.height = size;
    return d;
}

// Smooth blobs: values 0 .. ~200, transparent background.
inline double blobs(int i, int j, int k) {
    const glm::dvec3 p(i, j, k);
    return 180.0 *
               std::exp(-glm::dot(p - glm::dvec3(14, 16, 15), p - glm::dvec3(14, 16, 15)) / 40.0) +
           140.0 *
               std::exp(-glm::dot(p - glm::dvec3(24, 22, 20), p - glm::dvec3(24, 22, 20)) / 25.0);
}

inline ImageRGBA8 toImage(const std::vector<glm::vec4>& px, int w, int h) {
    ImageRGBA8 img = ImageRGBA8::filled(w, h, 255);
    for (int n = 0; n < w * h; ++n) {
        for (int c = 0; c < 3; ++c) {
            img.pixels[std::size_t(n) * 4 + c] =
                std::uint8_t(std::lround(std::clamp(px[n][c], 0.0f, 1.0f) * 255));
        }
    }
    return img;
}

// Blobs plus structure on every face of the box, so that rays sample and shade
// right at the borders, where kernels hand over to each other.
inline Volume facesAndBlobs(VoxelType type) {
    return makeVolume(
        {37, 33, 30},
        [](int i, int j, int k) {
            const bool face = i == 0 || j == 0 || k == 0 || i == 36 || j == 32 || k == 29;
            return blobs(i, j, k) + (face ? 90.0 + 3.0 * ((i + j + k) % 7) : 0.0);
        },
        type);
}

// Largest difference of any channel of any pixel.
inline float maxDifference(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b) {
    float worst = 0.0f;
    for (std::size_t n = 0; n < a.size(); ++n) {
        const glm::vec4 d = glm::abs(a[n] - b[n]);
        worst = std::max({worst, d.r, d.g, d.b, d.a});
    }
    return worst;
}

} // namespace lucent::test
