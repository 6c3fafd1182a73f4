#pragma once
// Scenes at the edges of what the ray casters accept, shared by the CPU and GL
// extremes suites, and the checks every image must pass: no NaN or Inf,
// opacity in [0, 1], premultiplied colour no brighter than its opacity allows.

#include <QString>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/image/ImageMetrics.h"
#include "core/raycast/CpuRayCaster.h"
#include "tests/core/raycast/RaycastScenes.h"

namespace lucent::test {

struct Scene {
    std::unique_ptr<Volume> volume;
    RenderDescription desc;
};

inline Scene scene(Volume v, TransferFunction tf, int size = 32) {
    Scene s;
    s.volume = std::make_unique<Volume>(std::move(v));
    s.desc = describe(*s.volume, std::move(tf), size);
    return s;
}

inline void setSpacing(Volume& v, glm::dvec3 spacing, glm::dvec3 origin = glm::dvec3(0.0)) {
    VolumeGeometry g = v.geometry();
    g.spacing = spacing;
    g.origin = origin;
    v.setGeometry(g);
}

// Opacity 0 below 99 and above 101, 1 at 100: one narrow spike, white.
inline TransferFunction spikeTf(double peak = 1.0) {
    TransferFunction tf;
    tf.name = "spike";
    tf.opacity = {{99.0, 0.0}, {100.0, peak}, {101.0, 0.0}};
    tf.colour = {{0.0, {1, 1, 1}}};
    tf.shading.enabled = false;
    return tf;
}

// Values 0 at j = 0 to 200 at j = dims.y - 1, linear: the anterior view's
// centre ray runs along j through it.
inline Volume rampVolume(int n = 33) {
    return makeVolume({n, n, n}, [n](int, int j, int) { return 200.0 * j / (n - 1); });
}

// rampTf with every value (and the volume's values) scaled by `scale`.
inline TransferFunction scaledRampTf(double scale, bool shading) {
    TransferFunction tf = rampTf(shading);
    for (auto& p : tf.opacity) {
        p.value *= scale;
    }
    for (auto& p : tf.colour) {
        p.value *= scale;
    }
    return tf;
}

inline Volume scaledBlobs(double scale) {
    return makeVolume({32, 32, 32},
                      [scale](int i, int j, int k) { return scale * blobs(i, j, k); });
}

// Every named scene; the CPU suite renders them in both precisions, the GL
// suite against the CPU reference.
inline std::vector<std::string> sceneNames() {
    return {"step-1e-4-tiny",
            "step-0.01",
            "step-10",
            "step-50",
            "step-1e6",
            "opacity-0",
            "opacity-1e-6",
            "opacity-1",
            "spike-post",
            "spike-preint",
            "int16-full-range",
            "float-1e-30-to-1e30",
            "float-1e-30",
            "float-1e30",
            "spacing-1-1-1000",
            "spacing-1e-3-1-1",
            "dims-1x1x1",
            "dims-1xNxN-face",
            "dims-1xNxN-edge",
            "dims-Nx1x1",
            "dims-2048x2048x4",
            "zoom-1e-3",
            "zoom-1e4",
            "origin-1km",
            "fov-170-corner",
            "grazing-clip",
            "grazing-axis",
            "preint-equal",
            "constant-shaded-linear",
            "constant-shaded-cubic",
            "constant-1e30",
            "brick-border"};
}

// Scenes of extreme sampling: tiny and huge steps, opacities, spikes, pre-integration
// of equal values, constant shaded volumes, samples on brick borders.
inline std::optional<Scene> samplingScene(const std::string& name) {
    const auto blobVolume = [] { return makeVolume({32, 32, 32}, blobs, VoxelType::Int16); };
    const auto constant = [](double value) {
        return makeVolume({16, 16, 16}, [value](int, int, int) { return value; });
    };
    if (name == "step-1e-4-tiny") {
        Scene s =
            scene(makeVolume({3, 3, 3}, [](int, int, int) { return 100.0; }), flatTf(0.3), 15);
        s.desc.sampling.step = 1e-4;
        return s;
    }
    if (name.rfind("step-", 0) == 0) {
        Scene s = scene(blobVolume(), rampTf(true));
        s.desc.sampling.step = std::stod(name.substr(5));
        return s;
    }
    if (name.rfind("opacity-", 0) == 0) {
        return scene(blobVolume(), flatTf(std::stod(name.substr(8)), true));
    }
    if (name.rfind("spike-", 0) == 0) {
        Scene s = scene(rampVolume(), spikeTf(), 33);
        s.desc.sampling.preintegrate = name == "spike-preint";
        return s;
    }
    if (name == "preint-equal") {
        Scene s = scene(constant(120.0), rampTf(false));
        s.desc.sampling.preintegrate = true;
        return s;
    }
    if (name.rfind("constant-shaded-", 0) == 0) {
        Scene s = scene(constant(120.0), rampTf(true));
        s.desc.sampling.interpolation =
            name == "constant-shaded-cubic" ? Interpolation::Cubic : Interpolation::Linear;
        return s;
    }
    if (name == "brick-border") {
        // Brick borders at multiples of 8 voxels; the centre ray runs along j
        // from j = 0, so with step 1 its samples fall exactly on them.
        Scene s = scene(makeVolume({33, 33, 33}, blobs, VoxelType::Int16), rampTf(true), 33);
        s.desc.sampling.brickSize = 8;
        s.desc.sampling.step = 1.0;
        return s;
    }
    return std::nullopt;
}

// Scenes of extreme voxel values: the whole int16 range, floats from 1e-30 to 1e30.
inline std::optional<Scene> valueScene(const std::string& name) {
    const auto constant = [](double value) {
        return makeVolume({16, 16, 16}, [value](int, int, int) { return value; });
    };
    if (name == "int16-full-range") {
        TransferFunction tf;
        tf.opacity = {{-32768.0, 0.05}, {0.0, 0.0}, {32767.0, 0.6}};
        tf.colour = {{-32768.0, {0, 0.3, 1}}, {32767.0, {1, 0.9, 0.8}}};
        Scene s = scene(makeVolume(
                            {32, 32, 32},
                            [](int i, int j, int k) {
                                if ((i + j + k) % 11 == 0) {
                                    return (i + j) % 2 ? 32767.0 : -32768.0; // neighbours jump
                                }
                                return -32768.0 + 65535.0 * blobs(i, j, k) / 200.0;
                            },
                            VoxelType::Int16),
                        tf);
        s.desc.sampling.interpolation = Interpolation::Cubic;
        return s;
    }
    if (name == "float-1e-30-to-1e30") {
        TransferFunction tf;
        tf.opacity = {{0.0, 0.02}, {1e28, 0.05}, {1e30, 0.7}};
        tf.colour = {{0.0, {0.2, 0.4, 1}}, {1e30, {1, 1, 1}}};
        Scene s = scene(makeVolume({32, 32, 32},
                                   [](int i, int j, int k) {
                                       const double t = blobs(i, j, k) / 200.0; // 0 .. ~1
                                       return std::pow(10.0, -30.0 + 60.0 * std::min(t, 1.0));
                                   }),
                        tf);
        s.desc.sampling.interpolation = Interpolation::Cubic;
        return s;
    }
    if (name == "float-1e-30" || name == "float-1e30") {
        const double scale = name == "float-1e-30" ? 1e-30 : 1e30;
        return scene(scaledBlobs(scale), scaledRampTf(scale, true));
    }
    if (name == "constant-1e30") {
        // 1e30 inside the ramp (0.5e30 .. 1.5e30): visible, so rays sample it.
        return scene(constant(1e30), scaledRampTf(1e28, true));
    }
    return std::nullopt;
}

// Scenes of extreme geometry: spacings, dimensions, zoom, a far origin, a wide field of
// view, clip faces and axes along the rays.
inline std::optional<Scene> geometryScene(const std::string& name) {
    const auto blobVolume = [] { return makeVolume({32, 32, 32}, blobs, VoxelType::Int16); };
    if (name == "spacing-1-1-1000" || name == "spacing-1e-3-1-1") {
        const bool thickZ = name == "spacing-1-1-1000";
        Volume v = makeVolume(
            thickZ ? glm::ivec3(16, 16, 4) : glm::ivec3(4, 16, 16), [](int i, int j, int k) {
                return 100.0 + 70.0 * std::sin(0.7 * i + 0.3 * k) * std::cos(0.5 * j - 0.4 * k);
            });
        setSpacing(v, thickZ ? glm::dvec3(1, 1, 1000) : glm::dvec3(1e-3, 1, 1));
        // A needle 15 x 15 x 3000 mm: the centre column's rays meet it.
        Scene s = scene(std::move(v), rampTf(true), 33);
        s.desc.camera.azimuth = thickZ ? 0.0 : 30.0;
        s.desc.camera.elevation = thickZ ? 10.0 : 40.0;
        return s;
    }
    if (name.rfind("dims-", 0) == 0) {
        glm::ivec3 dims{1, 1, 1};
        if (name.rfind("dims-1xNxN", 0) == 0) {
            dims = {1, 17, 17};
        } else if (name == "dims-Nx1x1") {
            dims = {17, 1, 1};
        } else if (name == "dims-2048x2048x4") {
            dims = {2048, 2048, 4};
        }
        Volume v = makeVolume(
            dims, [](int i, int j, int k) { return 60.0 + ((i / 128 + j / 128 + k) % 3) * 50.0; },
            VoxelType::Int16);
        Scene s = scene(std::move(v), rampTf(true), 33);
        s.desc.camera.azimuth = name == "dims-1xNxN-face" ? 90.0 : 0.0;
        s.desc.camera.elevation = name == "dims-2048x2048x4" ? 90.0 : 0.0;
        return s;
    }
    if (name.rfind("zoom-", 0) == 0) {
        Scene s = scene(blobVolume(), rampTf(true), 33);
        s.desc.camera.zoom = std::stod(name.substr(5));
        return s;
    }
    if (name == "origin-1km") {
        Volume v = blobVolume();
        setSpacing(v, glm::dvec3(0.5), glm::dvec3(1e6, -1e6, 1e6)); // a kilometre from the origin
        Scene s = scene(std::move(v), rampTf(true));
        s.desc.camera.azimuth = 20.0;
        return s;
    }
    if (name == "fov-170-corner") {
        // The eye sits on the bounding sphere, which touches the volume's
        // corner: the closest Camera allows to an eye inside the volume.
        Scene s = scene(blobVolume(), rampTf(true), 33);
        s.desc.camera.fieldOfView = 170.0;
        s.desc.camera.azimuth = 45.0;
        s.desc.camera.elevation = 35.26438968;
        return s;
    }
    if (name == "grazing-clip") {
        // The clip box's face x = 15.5 holds the eye and the centre column's rays.
        Scene s = scene(blobVolume(), rampTf(true), 33);
        s.desc.clip.lo.x = 15.5;
        return s;
    }
    if (name == "grazing-axis") {
        Scene s = scene(blobVolume(), rampTf(true), 33);
        s.desc.camera.azimuth = 90.0; // the x faces run along the rays
        s.desc.sampling.interpolation = Interpolation::Cubic;
        return s;
    }
    return std::nullopt;
}

inline Scene makeScene(const std::string& name) {
    for (const auto make : {samplingScene, valueScene, geometryScene}) {
        if (std::optional<Scene> s = make(name)) {
            return std::move(*s);
        }
    }
    throw std::invalid_argument("no scene " + name);
}

// Empty when every pixel is finite, opacity lies in [0, 1] and colour in
// [0, (ambient + diffuse + specular) * opacity]; otherwise what is wrong.
inline QString badPixels(const std::vector<glm::vec4>& px, const TransferFunction& tf) {
    const Shading& l = tf.shading;
    const float gain = l.enabled ? float(l.ambient + l.diffuse + l.specular) : 1.0f;
    int nonFinite = 0, badAlpha = 0, badColour = 0;
    for (const glm::vec4& p : px) {
        if (!std::isfinite(p.r) || !std::isfinite(p.g) || !std::isfinite(p.b) ||
            !std::isfinite(p.a)) {
            ++nonFinite;
        } else if (p.a < 0.0f || p.a > 1.0f + 1e-5f) {
            ++badAlpha;
        } else if (glm::any(glm::lessThan(glm::vec3(p), glm::vec3(-1e-6f))) ||
                   glm::any(glm::greaterThan(glm::vec3(p), glm::vec3(gain * p.a + 1e-4f)))) {
            ++badColour;
        }
    }
    if (nonFinite + badAlpha + badColour == 0) {
        return {};
    }
    return QString("%1 non-finite, %2 opacity outside [0,1], %3 colour outside [0, %4 a] of %5")
        .arg(nonFinite)
        .arg(badAlpha)
        .arg(badColour)
        .arg(double(gain))
        .arg(px.size());
}

inline glm::vec4 centrePixel(const RenderResult& r, int w, int h) {
    return r.premultiplied[std::size_t(h / 2) * std::size_t(w) + std::size_t(w / 2)];
}

inline double alphaSum(const std::vector<glm::vec4>& px) {
    double s = 0.0;
    for (const glm::vec4& p : px) {
        s += double(p.a);
    }
    return s;
}

} // namespace lucent::test
