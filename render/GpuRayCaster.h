#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/RenderDescription.h"
#include "core/scene/Renderer.h"
#include "core/volume/BrickLevels.h"
#include "core/volume/VolumePart.h"

namespace lucent {

struct GpuOptions {
    // Bytes the brick pool may take; 0: half of what the GPU reports, or
    // 1 GiB where the driver reports nothing (Mesa's llvmpipe).
    std::size_t budgetBytes = 0;
    // The B-spline coefficients in 32-bit floats (exact) or 16-bit floats (half the memory).
    bool halfFloatCoefficients = false;
    // Keep each resident brick's gradient with its voxels (8 bytes a texel in
    // all for int16 voxels, else 8 more) when the bricks the scene needs, at
    // the finest level the budget allows, fit it that way: shading then reads
    // one texel instead of six (nearest and trilinear). Either way the pool
    // holds only what the scene needs.
    bool gradientCache = true;
    // The most GPU memory the resident bricks may take with cached gradients,
    // as a share of the volume's own bytes; above it the gradients are
    // computed (0: no limit). Cached gradients take 4x the values of an int16
    // volume: on a CT whose visible boxes cover 3/4 of it, 3x the volume.
    double gradientCacheShare = 2.0;
    // Under a budget too small for level 0: each brick at the finest level the
    // budget allows for it, those worth most first (projected voxel size,
    // visible content, focus), or the whole volume at one level.
    LodPolicy lodPolicy = LodPolicy::PerBrick;
    // Bytes a frame may upload beyond what it must show (0: no cap). A brick
    // over the cap is shown from a coarser level already resident, and the
    // frame says how many still stream in (GpuFrameStats::pending).
    std::size_t uploadBytesPerFrame = 0;
    // Each brick holds only the box of its voxels the scene can show (false:
    // the whole brick wherever any of it shows; for comparisons).
    bool tightBricks = true;
};

// What a GPU frame did beyond the common statistics.
struct GpuFrameStats {
    std::size_t bricksUploaded = 0; // this frame
    std::size_t bytesUploaded = 0;  // this frame
    std::size_t bricksResident = 0;
    std::size_t residentBytes = 0; // GPU memory the resident bricks take (values and gradients)
    std::size_t valueBytes = 0;    // ... of that, their values
    std::size_t gradientBytes = 0; // ... and their cached gradients
    std::size_t tableBytes = 0;    // the page table, boxes, leaping cells and distance maps
    std::size_t poolBytes = 0;     // GPU memory the pool's textures take, free room included
    std::vector<std::size_t> bricksPerLevel; // bricks shown per level
    // Per brick of the pool (pages of pageSize voxels a side, x fastest): the
    // level it is drawn from, -1 where nothing of it is drawn.
    std::vector<std::int8_t> levelOfBrick;
    int pageSize = 0;
    std::size_t pagesShown = 0;
    std::size_t pending = 0; // bricks shown coarser than planned while they stream in
    std::size_t budgetBytes = 0;
    bool gradientsCached = false;
    std::string budgetSource; // where the budget came from
    std::string lodReason;    // why a coarser level, when one was used
    // This frame: the surface's mesh or field, uploaded when the display's pointers changed.
    std::size_t surfaceBytesUploaded = 0;
    // Where a read-back frame's time went (render(), not drawInPlace()): the
    // set-up and ray cast until the GPU finished, the read back, the conversion.
    double castMs = 0.0;
    double readMs = 0.0;
    double convertMs = 0.0;
    // CPU time of the frame before its draw call (bricks, tables, uniforms);
    // what a camera-only frame costs besides the cast itself.
    double prepareMs = 0.0;
    // What the frame rebuilt (render/BrickStreamer.h): the levels whose cell
    // masks and boxes it classified, whether it planned the bricks (octree,
    // levels, page table) anew and uploaded the page table. A frame that only
    // moved the camera over the same pages does none of these.
    int levelsClassified = 0;
    bool bricksPlanned = false;
    bool tableUploaded = false;
};

struct GpuRenderResult {
    RenderResult frame; // image, premultiplied colour and the common statistics (lod included)
    GpuFrameStats gpu;
};

// The GPU ray caster: the CPU reference's rays, lattice and filters in a
// fragment shader, over a pool of bricks that holds only what the current
// transfer function and clip box need, at the finest level of detail that
// fits the budget. Needs a current OpenGL 4.3 core context (an
// OffscreenContext, or a QOpenGLWidget's) for its whole life.
class GpuRayCaster : public Renderer {
public:
    // Throws GlError when the context is missing or too old or the shaders fail.
    explicit GpuRayCaster(const Volume& volume, GpuOptions options = {});
    // A caster of one part of a volume (a rank of a distributed render), as
    // CpuRayCaster(part, where): its owned box on the whole volume's lattice
    // and view, over transparent black; MIP, MinIP and average also give the
    // values they composite from (RenderResult::projection).
    GpuRayCaster(const Volume& part, const VolumePart& where, GpuOptions options = {});
    ~GpuRayCaster() override;
    GpuRayCaster(const GpuRayCaster&) = delete;
    GpuRayCaster& operator=(const GpuRayCaster&) = delete;

    // Renders and reads the image back (PNG output, thumbnails, the server).
    // Throws std::invalid_argument for a setting out of range, BudgetError
    // when even the coarsest level does not fit the budget, GlError when the
    // driver refuses.
    RenderResult render(const RenderDescription& description) override;
    // The same, with what the frame did on the GPU.
    GpuRenderResult renderWithGpuStats(const RenderDescription& description);

    // Shows `surface` with the volume from the next frame on, each occluding
    // the other; null: none. The surface is drawn first for the same camera
    // (render/SurfaceRenderer.h): per pixel its lit colour and the distance tS
    // from the eye along the pixel's ray, in the rays' parameter t (mm). A ray
    // takes sample n only while t0 + n * dt < tS: a sample exactly at the
    // surface belongs to the surface. The ray's premultiplied colour is then
    // composited over the opaque surface, ray + (1 - ray.a) * surface, where
    // there is one (the background no longer shows there), in the ray pass
    // itself: render()'s premultiplied frame and drawInPlace() both get it and
    // add the background as before. MIP, MinIP and average project only the
    // samples in front of the surface, composited over it the same way.
    // showVolume false: no bricks, no rays (no samples); the frame is the
    // surface over the background. Needs no context (the mesh is uploaded
    // with the next frame). Throws std::invalid_argument for a display
    // checkSurfaceDisplay() refuses, and std::logic_error on a part caster: a
    // part of a distributed render draws volumes only. Returns true.
    bool setSurface(std::shared_ptr<const SurfaceDisplay> surface) override;

    bool drawsInPlace() const override { return true; }
    // Ray casts into the caster's float target as render() does, then draws
    // that frame with one triangle into `target` (a framebuffer of the current
    // context), composited over the description's background in the shader;
    // nothing is read back but one count a row for the statistics' samples. A
    // frame smaller than the rectangle (an interactive one) is composited at
    // its size into 8 bits and stretched by the sampler, as scaledTo()
    // stretches the read back image (bilinear, pixel centres aligned). A
    // description that differs from the last one cast in nothing but its
    // background is not cast again: a repaint of the same frame (an overlay
    // changed, a screenshot) draws the frame kept, and returns its statistics.
    // Leaves target.framebuffer bound with the rectangle as the viewport, and
    // no program, vertex array or texture of the caster's bound. Throws as
    // render(), and std::invalid_argument for an empty rectangle.
    RenderStats drawInPlace(const RenderDescription& description,
                            const FramebufferTarget& target) override;
    std::string backend() const override { return "gl"; }
    // The GL renderer and version of the current context.
    std::string device() const override;
    // The last frame's GpuFrameStats as key=value pairs (uploads, pool, gradients).
    FrameDetails frameDetails() const override;
    const GpuFrameStats& lastFrame() const;

private:
    struct State;
    // Ray casts into the float target: the statistics but the samples, and
    // what the frame did on the GPU; no image. countRows: the shader also
    // counts the samples per row (RenderTarget::countedSamples()).
    GpuRenderResult cast(const RenderDescription& description, bool countRows);

    std::unique_ptr<State> state_;
};

// Clears the rectangle of `target` (a framebuffer of the current context) to
// `colour`, opaque: what the 3D view shows where it has no frame to draw.
// Leaves target.framebuffer bound with the rectangle as the viewport. Throws
// GlError when the driver reports an error.
void clearFramebuffer(const FramebufferTarget& target, const glm::dvec3& colour);

} // namespace lucent
