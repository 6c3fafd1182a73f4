#pragma once
// Where the render thread's frames are drawn: in this process
// (LocalFrameSource: the series loaded whole, rendered on its RenderDevice) or
// by all the ranks of an MPI job (DistributedFrameSource). RenderWorker asks
// it for images and encodes them; everything runs on the render thread.

#include <QString>

#include <memory>
#include <vector>

#include <glm/glm.hpp>
#include <stdexcept>

#include "core/image/Image.h"
#include "core/io/SeriesEntry.h"
#include "core/scene/RenderDescription.h"
#include "core/scene/Renderer.h"
#include "core/volume/Volume.h"

namespace lucent::remote {

class FrameSource {
public:
    virtual ~FrameSource() = default;
    // Opens what renders (an EGL context, or the CPU where GL cannot be had);
    // says what renders, and why not what was asked.
    virtual QString start() = 0;
    // Frees the renderers (and the context while it is current).
    virtual void stop() = 0;
    // The frame of `description` (its volume ignored) of `series`: its image,
    // and its other buffers where the renderer fills them. Throws on failure,
    // with a message for the client.
    virtual RenderResult render(const std::shared_ptr<const SeriesEntry>& series,
                                const RenderDescription& description) = 0;
    // A frame `render` gave for `series`, encoded and no longer needed: a source
    // may draw its next frame of that size into it (Renderer::recycle). The
    // default drops it.
    virtual void recycle(const std::shared_ptr<const SeriesEntry>& /*series*/,
                         RenderResult&& /*frame*/) {}
    // A mark's points (fractions of the image of `description`) anchored on the
    // surface they show (core/raycast/SurfaceDepth.h). Throws on failure, with a
    // message for the client.
    virtual std::vector<glm::dvec3> surfaceAnchors(const std::shared_ptr<const SeriesEntry>& series,
                                                   const RenderDescription& description,
                                                   const std::vector<glm::dvec2>& fractions) = 0;
    // The whole volume of `series`, for MPR slices. Throws where no rank holds it whole.
    virtual const Volume& volume(const std::shared_ptr<const SeriesEntry>& /*series*/) {
        throw std::runtime_error("MPR slices need the whole volume in the server's process; "
                                 "this server renders it in parts on several ranks");
    }
};

} // namespace lucent::remote
