#pragma once
// One way into rendering: what every renderer does with a RenderDescription,
// whatever runs it (the CPU reference ray caster, the GPU ray caster, later a
// renderer spread over several processes). Callers get one from the opener in
// render/RenderDevice.h, which picks GL or CPU and says why it fell back.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/image/Image.h"
#include "core/scene/RenderDescription.h"

namespace lucent {

struct SurfaceDisplay; // core/scene/SurfaceDisplay.h

struct RenderStats {
    std::size_t samples = 0;     // volume samples taken along all rays
    std::size_t bricksTotal = 0; // bricks of the volume
    std::size_t bricksUsed = 0;  // bricks visible under the transfer function and clip box
    int lod = 0;                 // level of detail rendered (0: full resolution)
    std::string lodReason;       // why a coarser level, when one was used
    // Bricks drawn from a coarser level than planned while the finer ones
    // stream in (the GPU renderer under an upload cap): another frame of the
    // same view shows more.
    std::size_t bricksPending = 0;
};

struct RenderResult {
    ImageRGBA8 image;                     // opaque: composited over the background
    std::vector<glm::vec4> premultiplied; // per pixel, before the background (row-major)
    // A part of a volume (a rank of a distributed render) in MIP, MinIP or
    // average: per pixel the projected value and 1, or the sum of the samples
    // and their count; (0, 0) where the ray took no sample. Empty otherwise.
    std::vector<glm::vec2> projection;
    RenderStats stats;
};

// A framebuffer of the OpenGL context current on the caller's thread, and the
// rectangle of it (pixels, origin bottom left) that a frame fills.
struct FramebufferTarget {
    unsigned framebuffer = 0;
    int x = 0, y = 0, width = 0, height = 0;
};

// Figures of the last frame beyond RenderStats, in the order --stats prints them.
using FrameDetails = std::vector<std::pair<std::string, std::string>>;

// The figure named `key`, or nullopt where the renderer gives none.
inline std::optional<std::string> frameDetail(const FrameDetails& details, std::string_view key) {
    for (const auto& [name, value] : details) {
        if (name == key) {
            return value;
        }
    }
    return std::nullopt;
}

class Renderer {
public:
    virtual ~Renderer() = default;

    // Renders the description (its volume must be the renderer's, or null) and
    // returns the image. Throws std::invalid_argument naming a setting out of
    // range; a GL renderer also GlError or BudgetError (render/GlError.h).
    virtual RenderResult render(const RenderDescription& description) = 0;

    // "cpu" or "gl".
    virtual std::string backend() const = 0;
    // What runs it, in words ("llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa").
    virtual std::string device() const = 0;
    // The last frame's own figures (uploads, pool, gradients...), as key=value pairs.
    virtual FrameDetails frameDetails() const { return {}; }

    // Hands back a frame this renderer returned, once its caller is done with
    // it: a renderer may draw the next frame of that size into its buffers
    // instead of allocating new ones (the CPU ray caster does). Optional; the
    // default drops it.
    virtual void recycle(RenderResult&& spent) { (void)spent; }

    // Whether drawInPlace() works: a renderer that draws with OpenGL can put a
    // frame straight into a framebuffer of the current context, with no read back.
    virtual bool drawsInPlace() const { return false; }
    // Draws the description's frame into `target`, scaled to its rectangle, over
    // the description's background. Throws std::logic_error where !drawsInPlace().
    virtual RenderStats drawInPlace(const RenderDescription& description,
                                    const FramebufferTarget& target);

    // Shows `surface` with the volume from the next frame on, each occluding
    // the other; null: none. Returns whether this renderer draws surfaces:
    // the default (the CPU ray caster, a distributed render) ignores it.
    virtual bool setSurface(std::shared_ptr<const SurfaceDisplay> surface) {
        (void)surface;
        return false;
    }
};

} // namespace lucent
