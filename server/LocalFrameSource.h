#pragma once
// Frames drawn in this process: each series a client opens loaded whole and
// rendered on the RenderDevice (GL or CPU) opened on the render thread; the
// last two series kept loaded.

#include <list>
#include <memory>

#include "render/RenderDevice.h"
#include "server/FrameSource.h"

namespace lucent::remote {

class LocalFrameSource : public FrameSource {
public:
    explicit LocalFrameSource(RendererKind backend);
    ~LocalFrameSource() override;

    QString start() override;
    void stop() override;
    ImageRGBA8 render(const std::shared_ptr<const SeriesEntry>& series,
                      const RenderDescription& description) override;
    std::vector<glm::dvec3> surfaceAnchors(const std::shared_ptr<const SeriesEntry>& series,
                                           const RenderDescription& description,
                                           const std::vector<glm::dvec2>& fractions) override;
    const Volume& volume(const std::shared_ptr<const SeriesEntry>& series) override;

private:
    struct LoadedSeries;
    // The loaded volume of exactly this entry: a series the store has grown since
    // (a new entry with the same id) is loaded again.
    LoadedSeries& loaded(const std::shared_ptr<const SeriesEntry>& entry);

    RendererKind backend_;
    std::unique_ptr<RenderDevice> device_;            // made on the render thread by start()
    std::list<std::unique_ptr<LoadedSeries>> loaded_; // most recently used first
};

} // namespace lucent::remote
