#pragma once
// The scenes of test_surface_in_volume and what they should show, computed on
// the CPU: a volume with a fog, a layer and a slab along the view; meshes
// (quads across the view, boxes); surface.frag's headlight in double.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/image/Image.h"
#include "core/scene/Renderer.h"
#include "core/scene/SurfaceDisplay.h"
#include "core/scene/ViewFrame.h"
#include "tests/core/raycast/RaycastScenes.h"

namespace lucent::test {

constexpr double kPlaneY = 19.3; // through the volume's middle, between voxel planes

// 40^3 voxels, index = LPS mm. A fog everywhere, brighter along y (the view);
// a dense layer at j 17..22 that the plane cuts; a slab at j >= 34.
inline Volume sceneVolume() {
    return makeVolume(
        {40, 40, 40},
        [](int i, int j, int k) {
            if (j >= 34) {
                return 600.0;
            }
            if (j >= 17 && j <= 22) {
                return 250.0 + 8.0 * (j - 17) + 10.0 * std::sin((i + k) / 3.0);
            }
            return 60.0 + 25.0 * (1.0 + std::sin(i / 4.0) * std::cos(k / 5.0)) + 2.0 * j;
        },
        VoxelType::Int16);
}

// Fog and layer (the slab too): what the plane test composites.
inline TransferFunction layerTf() {
    TransferFunction tf;
    tf.name = "layer";
    tf.opacity = {{0, 0},      {50, 0.01}, {200, 0.02}, {235, 0.05},
                  {260, 0.25}, {310, 0.3}, {600, 0.7}};
    tf.colour = {{0, {0.3, 0.5, 1.0}},
                 {200, {0.4, 1.0, 0.5}},
                 {250, {1.0, 0.3, 0.1}},
                 {310, {0.9, 0.1, 0.6}},
                 {600, {1, 1, 1}}};
    return tf;
}

// The slab alone: nothing in front of it shows.
inline TransferFunction slabTf() {
    TransferFunction tf;
    tf.name = "slab";
    tf.opacity = {{0, 0}, {450, 0}, {600, 0.95}};
    tf.colour = {{0, {1, 1, 1}}, {600, {0.95, 0.95, 0.9}}};
    return tf;
}

using Mesh = std::shared_ptr<const TriangleMesh>;

// A quad at y in x [x0, x1], z [z0, z1] (facing -y), two triangles.
inline Mesh quadAt(double y, double x0, double x1, double z0 = -200.0, double z1 = 240.0) {
    auto m = std::make_shared<TriangleMesh>();
    m->vertices = {{x0, y, z0}, {x1, y, z0}, {x1, y, z1}, {x0, y, z1}};
    m->triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

// A closed box, each face its own four vertices (flat normals), wound
// counter-clockwise from outside.
inline Mesh box(glm::dvec3 lo, glm::dvec3 hi) {
    auto m = std::make_shared<TriangleMesh>();
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const auto corner = [&](int a, int b) {
                glm::dvec3 p;
                p[axis] = side ? hi[axis] : lo[axis];
                p[u] = a ? hi[u] : lo[u];
                p[v] = b ? hi[v] : lo[v];
                return p;
            };
            const auto first = std::uint32_t(m->vertices.size());
            m->vertices.insert(m->vertices.end(),
                               {corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)});
            // (u, v, axis) is right-handed: counter-clockwise in u, v faces +axis.
            if (side) {
                m->triangles.insert(m->triangles.end(),
                                    {{first, first + 1, first + 2}, {first, first + 2, first + 3}});
            } else {
                m->triangles.insert(m->triangles.end(),
                                    {{first, first + 2, first + 1}, {first, first + 3, first + 2}});
            }
        }
    }
    return m;
}

inline std::shared_ptr<const SurfaceDisplay> plain(Mesh mesh, glm::dvec3 colour,
                                                   bool volume = true) {
    auto d = std::make_shared<SurfaceDisplay>();
    d->mesh = std::move(mesh);
    d->colour = colour;
    d->showVolume = volume;
    return d;
}

// surface.frag's headlight, in double.
inline glm::dvec3 lit(glm::dvec3 base, glm::dvec3 normal, glm::dvec3 ray, const Shading& s) {
    const double ndotl = std::min(1.0, std::abs(glm::dot(glm::normalize(normal), ray)));
    const glm::dvec3 c = base * (s.ambient + s.diffuse * ndotl) +
                         glm::dvec3(s.specular * std::pow(ndotl, s.specularPower));
    return glm::clamp(c, 0.0, 1.0);
}

// The largest channel difference of pixel (x, y) from a colour or another image's.
inline int differenceAt(const ImageRGBA8& image, int x, int y, glm::dvec3 colour) {
    int most = 0;
    for (int c = 0; c < 3; ++c) {
        most =
            std::max(most, std::abs(int(image.at(x, y, c)) - int(std::lround(colour[c] * 255.0))));
    }
    return most;
}
inline int differenceAt(const ImageRGBA8& a, const ImageRGBA8& b, int x, int y) {
    int most = 0;
    for (int c = 0; c < 4; ++c) {
        most = std::max(most, std::abs(int(a.at(x, y, c)) - int(b.at(x, y, c))));
    }
    return most;
}

// The CPU's clipped frame composited over the plane facing the view, lit per
// pixel, then over the background, as GpuRayCaster::render converts.
inline ImageRGBA8 overPlane(const RenderResult& cpu, const RenderDescription& d,
                            glm::dvec3 colour) {
    const ViewFrame f = makeViewFrame(d.volume->geometry(), d.camera, d.width, d.height);
    ImageRGBA8 image = ImageRGBA8::filled(d.width, d.height, 255);
    for (int y = 0; y < d.height; ++y) {
        for (int x = 0; x < d.width; ++x) {
            const glm::dvec4 ray(cpu.premultiplied[std::size_t(y) * d.width + x]);
            const glm::dvec3 surface =
                lit(colour, {0, 1, 0}, f.rayDirection(x, y, d.width, d.height),
                    d.transferFunction.shading);
            const glm::dvec3 rgb = glm::dvec3(ray) + (1.0 - ray.a) * surface; // opaque now
            for (int c = 0; c < 3; ++c) {
                image.at(x, y, c) = std::uint8_t(std::clamp(rgb[c], 0.0, 1.0) * 255.0 + 0.5);
            }
        }
    }
    return image;
}

// Pixels (x, y from the top) a set of points' projections bound.
struct ScreenBox {
    double x0 = 1e30, x1 = -1e30, y0 = 1e30, y1 = -1e30;
    bool inside(int x, int y, double margin) const {
        return x >= x0 + margin && x <= x1 - margin && y >= y0 + margin && y <= y1 - margin;
    }
};
inline ScreenBox screenBox(const RenderDescription& d, const std::vector<glm::dvec3>& points) {
    const ViewFrame f = makeViewFrame(d.volume->geometry(), d.camera, d.width, d.height);
    ScreenBox b;
    for (const glm::dvec3& p : points) {
        const glm::dvec3 v = p - f.eye;
        const double depth = glm::dot(v, f.forward);
        const double x =
            (glm::dot(v, f.right) / depth / (f.tanHalfFov * f.aspect) + 1.0) * d.width / 2 - 0.5;
        const double y = (1.0 - glm::dot(v, f.up) / depth / f.tanHalfFov) * d.height / 2 - 0.5;
        b = {std::min(b.x0, x), std::max(b.x1, x), std::min(b.y0, y), std::max(b.y1, y)};
    }
    return b;
}

inline int maxDifference(const ImageRGBA8& a, const ImageRGBA8& b) {
    int most = 0;
    for (int y = 0; y < a.height; ++y) {
        for (int x = 0; x < a.width; ++x) {
            most = std::max(most, differenceAt(a, b, x, y));
        }
    }
    return most;
}

} // namespace lucent::test
