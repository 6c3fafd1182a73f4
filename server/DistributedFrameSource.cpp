#include "server/DistributedFrameSource.h"

#include <stdexcept>

namespace lucent::remote {
namespace {

// Entries whose numbers are kept (more than the series kept open).
constexpr std::size_t kNumberedEntries = 16;

} // namespace

DistributedFrameSource::DistributedFrameSource(const Communicator& comm, RendererKind backend)
    : comm_(comm), backend_(backend) {}

DistributedFrameSource::~DistributedFrameSource() {
    stop();
}

QString DistributedFrameSource::start() {
    series_ = std::make_unique<DistributedSeries>(comm_, backend_);
    return QString("distributed: %1 ranks, %2 each (IceT)")
        .arg(comm_.size())
        .arg(rendererKindName(backend_));
}

void DistributedFrameSource::stop() {
    if (series_) {
        series_->release();
        series_.reset();
    }
}

std::uint64_t DistributedFrameSource::numberOf(const std::shared_ptr<const SeriesEntry>& series) {
    for (const auto& [entry, number] : numbers_) {
        if (entry == series) {
            return number;
        }
    }
    if (numbers_.size() >= kNumberedEntries) {
        numbers_.pop_front();
    }
    numbers_.emplace_back(series, next_);
    return next_++;
}

RenderResult DistributedFrameSource::render(const std::shared_ptr<const SeriesEntry>& series,
                                            const RenderDescription& description) {
    if (!series_) {
        throw std::logic_error("DistributedFrameSource: render() before start()");
    }
    return series_->lead(renderCommand(numberOf(series), *series, description), *series);
}

std::vector<glm::dvec3>
DistributedFrameSource::surfaceAnchors(const std::shared_ptr<const SeriesEntry>&,
                                       const RenderDescription&, const std::vector<glm::dvec2>&) {
    throw std::runtime_error("marks cannot be anchored by a distributed server: each rank holds "
                             "only a part of the volume (the pointer works)");
}

} // namespace lucent::remote
