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
    RenderResult render(const std::shared_ptr<const SeriesEntry>& series,
                        const RenderDescription& description) override;
    // Hands the frame back to the series' renderer (the CPU caster draws the
    // next frame of its size into it); dropped where the series is no longer loaded.
    void recycle(const std::shared_ptr<const SeriesEntry>& series, RenderResult&& frame) override;
    std::vector<glm::dvec3> surfaceAnchors(const std::shared_ptr<const SeriesEntry>& series,
                                           const RenderDescription& description,
                                           const std::vector<glm::dvec2>& fractions) override;
    const Volume& volume(const std::shared_ptr<const SeriesEntry>& series) override;
    // The renderer's figures of the last frame of `series` (Renderer::frameDetails);
    // empty where it is not loaded. On the render thread, like render().
    FrameDetails lastFrameDetails(const std::shared_ptr<const SeriesEntry>& series) const;

private:
    struct LoadedSeries;
    // The loaded volume of exactly this entry: a series the store has grown since
    // (a new entry with the same id) is loaded again.
    LoadedSeries& loaded(const std::shared_ptr<const SeriesEntry>& entry);
    // That entry where it is loaded, without loading it; null otherwise.
    LoadedSeries* findLoaded(const std::shared_ptr<const SeriesEntry>& entry);
    const LoadedSeries* findLoaded(const std::shared_ptr<const SeriesEntry>& entry) const;

    RendererKind backend_;
    std::unique_ptr<RenderDevice> device_;            // made on the render thread by start()
    std::list<std::unique_ptr<LoadedSeries>> loaded_; // most recently used first
};

} // namespace lucent::remote
