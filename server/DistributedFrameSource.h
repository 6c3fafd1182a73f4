#pragma once
// Frames drawn by all the ranks of an MPI job (lucent-server --distributed,
// docs/distributed.md): on rank 0's render thread, every frame is broadcast
// to the ranks, each renders its part of the series, IceT composites, and
// rank 0 gets the image, as ParaView's pvserver serves one volume from many
// processes. The other ranks run DistributedSeries::follow().

#include <cstdint>
#include <deque>
#include <utility>

#include "render/distributed/DistributedSeries.h"
#include "server/FrameSource.h"

namespace lucent::remote {

class DistributedFrameSource : public FrameSource {
public:
    // `comm` (rank 0 of it) must outlive the source.
    DistributedFrameSource(const Communicator& comm, RendererKind backend);
    ~DistributedFrameSource() override;

    QString start() override;
    // Releases the other ranks (they return from follow()).
    void stop() override;
    RenderResult render(const std::shared_ptr<const SeriesEntry>& series,
                        const RenderDescription& description) override;
    // Refused: the volume lies in parts on the ranks, none holds a whole ray.
    std::vector<glm::dvec3> surfaceAnchors(const std::shared_ptr<const SeriesEntry>& series,
                                           const RenderDescription& description,
                                           const std::vector<glm::dvec2>& fractions) override;

private:
    // Rank 0's number for an entry (the same entry, the same number).
    std::uint64_t numberOf(const std::shared_ptr<const SeriesEntry>& series);

    const Communicator& comm_;
    RendererKind backend_;
    std::unique_ptr<DistributedSeries> series_;
    // Entries seen lately with their numbers (held, so that an address is
    // never reused for another entry while it is listed).
    std::deque<std::pair<std::shared_ptr<const SeriesEntry>, std::uint64_t>> numbers_;
    std::uint64_t next_ = 1;
};

} // namespace lucent::remote
