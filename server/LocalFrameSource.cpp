#include "server/LocalFrameSource.h"

#include <utility>

#include "core/io/Catalog.h"
#include "core/raycast/SurfaceDepth.h"
#include "core/scene/Renderer.h"

namespace lucent::remote {
namespace {

// Series kept loaded (with their ray casters) at once.
constexpr std::size_t kLoadedSeriesLimit = 2;

} // namespace

struct LocalFrameSource::LoadedSeries {
    std::shared_ptr<const SeriesEntry> entry; // held: its address identifies it
    std::unique_ptr<Volume> volume;
    std::unique_ptr<Renderer> renderer;
};

LocalFrameSource::LocalFrameSource(RendererKind backend) : backend_(backend) {}

LocalFrameSource::~LocalFrameSource() {
    stop();
}

QString LocalFrameSource::start() {
    device_ = RenderDevice::open(backend_);
    const QString description = QString::fromStdString(device_->description());
    if (!device_->fallbackReason().empty()) {
        return description + " (" + QString::fromStdString(device_->fallbackReason()) + ")";
    }
    return description;
}

void LocalFrameSource::stop() {
    loaded_.clear(); // each GL renderer frees its textures in its own context
    device_.reset();
}

const LocalFrameSource::LoadedSeries*
LocalFrameSource::findLoaded(const std::shared_ptr<const SeriesEntry>& entry) const {
    for (const auto& series : loaded_) {
        if (series->entry == entry) {
            return series.get();
        }
    }
    return nullptr;
}

LocalFrameSource::LoadedSeries*
LocalFrameSource::findLoaded(const std::shared_ptr<const SeriesEntry>& entry) {
    return const_cast<LoadedSeries*>(std::as_const(*this).findLoaded(entry));
}

LocalFrameSource::LoadedSeries&
LocalFrameSource::loaded(const std::shared_ptr<const SeriesEntry>& entry) {
    for (auto it = loaded_.begin(); it != loaded_.end(); ++it) {
        if ((*it)->entry == entry) {
            loaded_.splice(loaded_.begin(), loaded_, it);
            return *loaded_.front();
        }
    }
    while (loaded_.size() >= kLoadedSeriesLimit) {
        loaded_.pop_back();
    }
    auto series = std::make_unique<LoadedSeries>();
    series->entry = entry;
    series->volume = std::make_unique<Volume>(loadSeries(*entry));
    // Where GL fails for this series (its shaders, its size), the CPU renders it.
    series->renderer = device_->openRenderer(*series->volume).renderer;
    loaded_.push_front(std::move(series));
    return *loaded_.front();
}

RenderResult LocalFrameSource::render(const std::shared_ptr<const SeriesEntry>& entry,
                                      const RenderDescription& description) {
    LoadedSeries& series = loaded(entry);
    RenderDescription d = description;
    d.volume = series.volume.get();
    return series.renderer->render(d);
}

void LocalFrameSource::recycle(const std::shared_ptr<const SeriesEntry>& entry,
                               RenderResult&& frame) {
    if (LoadedSeries* series = findLoaded(entry)) {
        series->renderer->recycle(std::move(frame));
    }
}

FrameDetails
LocalFrameSource::lastFrameDetails(const std::shared_ptr<const SeriesEntry>& entry) const {
    const LoadedSeries* series = findLoaded(entry);
    return series != nullptr ? series->renderer->frameDetails() : FrameDetails{};
}

std::vector<glm::dvec3>
LocalFrameSource::surfaceAnchors(const std::shared_ptr<const SeriesEntry>& entry,
                                 const RenderDescription& description,
                                 const std::vector<glm::dvec2>& fractions) {
    RenderDescription d = description;
    d.volume = loaded(entry).volume.get();
    return lucent::surfaceAnchors(d, fractions);
}

const Volume& LocalFrameSource::volume(const std::shared_ptr<const SeriesEntry>& entry) {
    return *loaded(entry).volume;
}

} // namespace lucent::remote
