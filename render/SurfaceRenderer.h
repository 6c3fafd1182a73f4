#pragma once
// The surface pass of the GPU ray caster (GpuRayCaster::setSurface): a
// SurfaceDisplay's mesh drawn for the rays' camera into a float target of the
// frame's size, lit, with each pixel's eye distance along its ray (the ray
// parameter t of raycast.frag), where the ray caster stops that pixel's ray.

#include <cstddef>
#include <memory>
#include <vector>

#include "core/scene/SurfaceDisplay.h"
#include "core/scene/ViewFrame.h"
#include "core/tf/TransferFunction.h"

namespace lucent {

// Throws std::invalid_argument when a triangle names a vertex the mesh lacks,
// the field's length is not the vertex count, or the mesh is too large to
// draw with 32-bit counts. GL-free.
void checkSurfaceDisplay(const SurfaceDisplay& display);

class SurfaceRenderer {
public:
    // Compiles the shaders and makes the colour map; needs the current context
    // for the renderer's whole life. Throws GlError when the driver refuses.
    SurfaceRenderer();
    ~SurfaceRenderer();
    SurfaceRenderer(const SurfaceRenderer&) = delete;
    SurfaceRenderer& operator=(const SurfaceRenderer&) = delete;

    // Draws `display` (checked by checkSurfaceDisplay) as the rays of `frame`
    // see it in a width x height image: pixel centres on the rays, nearest
    // surface in front, back faces too. Lit by a headlight with `light`'s
    // ambient, diffuse, specular and power, two-sided, whether or not the
    // volume is shaded. The mesh (positions relative to its centre, normals,
    // triangles) is uploaded when the display's mesh pointer differs from the
    // last one drawn, the field when its pointer does. Returns the bytes
    // uploaded. Leaves no depth test, program, vertex array or texture bound.
    std::size_t draw(const SurfaceDisplay& display, const ViewFrame& frame, const Shading& light,
                     int width, int height);

    // GL texture names. The last draw's premultiplied colour (RGBA32F, row 0
    // at the bottom): opaque where the surface is, transparent black elsewhere.
    unsigned colour() const;
    // The last draw's distances (R32F): mm from the eye along the pixel's ray
    // to the nearest surface, +inf where there is none.
    unsigned distance() const;
    // Copies colour() into `texture`, an RGBA32F texture of the same size.
    void copyColourTo(unsigned texture) const;

private:
    struct Gl;
    std::unique_ptr<Gl> gl_;
};

} // namespace lucent
