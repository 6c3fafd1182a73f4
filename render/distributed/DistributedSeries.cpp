#include "render/distributed/DistributedSeries.h"

#include <algorithm>
#include <filesystem>
#include <optional>

#include "core/io/Catalog.h"
#include "core/raycast/PartHalo.h"
#include "render/distributed/DistributedRenderer.h"
#include "render/distributed/PartLoader.h"
#include "render/distributed/RankAgreement.h"

namespace lucent {
namespace {

// Series kept open at once, as RenderWorker keeps them in one process.
constexpr std::size_t kOpenLimit = 2;
// How long an idle following rank sleeps between looks for a command.
constexpr std::chrono::microseconds kIdlePoll(1000);

// The description a part is read for: the asked interpolation (or a wider one
// read before) and twice the step, so that interactive frames (whose step
// doubles) need no second read.
RenderDescription readFor(const RankCommand& command, std::optional<Interpolation> before) {
    RenderDescription d = command.description;
    if (before) {
        d.sampling.interpolation = std::max(d.sampling.interpolation, *before);
    }
    d.sampling.step *= 2.0;
    return d;
}

// The bricks the volume is split by: the description's size, halved (down to
// 8) until there are at least as many bricks as ranks, since a client of the
// server cannot choose the split as the CLI's --brick does.
int splitBrickSize(glm::ivec3 dims, int ranks, int asked) {
    int size = asked;
    while (size > 8) {
        const glm::ivec3 bricks = (dims + size - 1) / size;
        if (std::int64_t(bricks.x) * bricks.y * bricks.z >= ranks) {
            break;
        }
        size /= 2;
    }
    return size;
}

} // namespace

struct DistributedSeries::Open {
    std::uint64_t series = 0;
    Interpolation interpolation = Interpolation::Linear;
    std::unique_ptr<DistributedRenderer> renderer;
};

DistributedSeries::DistributedSeries(const Communicator& comm, RendererKind kind)
    : comm_(comm), kind_(kind) {}

DistributedSeries::~DistributedSeries() = default;

RenderResult DistributedSeries::lead(const RankCommand& command, const SeriesEntry& entry) {
    std::string text = encodeRankCommand(command);
    comm_.broadcastPolled(text, 0, kIdlePoll);
    return carryOut(command, &entry);
}

void DistributedSeries::release() {
    if (released_ || comm_.rank() != 0) {
        return;
    }
    std::string text = encodeRankCommand(RankCommand{});
    comm_.broadcastPolled(text, 0, kIdlePoll);
    released_ = true;
}

void DistributedSeries::follow() {
    for (;;) {
        std::string text;
        comm_.broadcastPolled(text, 0, kIdlePoll);
        const RankCommand command = decodeRankCommand(text); // rank 0 wrote it
        if (command.kind == RankCommand::Kind::Stop) {
            return;
        }
        try {
            (void)carryOut(command, nullptr);
        } catch (const DistributedError&) {
            // Every rank knows; rank 0 tells the client. Wait for the next frame.
        } catch (const std::invalid_argument&) {
            // The same description is refused on every rank alike.
        }
    }
}

RenderResult DistributedSeries::carryOut(const RankCommand& command, const SeriesEntry* entry) {
    Open& open = opened(command, entry);
    return open.renderer->render(command.description);
}

DistributedSeries::Open& DistributedSeries::opened(const RankCommand& command,
                                                   const SeriesEntry* entry) {
    const int needed =
        partHalo(command.description.sampling.interpolation, command.description.sampling.step);
    std::optional<Interpolation> before;
    for (auto it = open_.begin(); it != open_.end(); ++it) {
        if ((*it)->series != command.series) {
            continue;
        }
        if ((*it)->renderer->part().halo >= needed) {
            open_.splice(open_.begin(), open_, it);
            return *open_.front();
        }
        // Read again with the halo this description needs (a cubic frame
        // after linear ones).
        before = (*it)->interpolation;
        open_.erase(it);
        break;
    }
    while (open_.size() >= kOpenLimit) {
        open_.pop_back();
    }
    // The entry as rank 0 serves it: the other ranks scan its folder.
    std::optional<SeriesEntry> found;
    onEveryRank(comm_, "finding series " + command.seriesId, [&] {
        if (entry != nullptr) {
            return;
        }
        const Catalog catalog = scanPath(command.seriesRoot);
        const SeriesEntry* e = catalog.find(command.seriesId);
        if (e == nullptr && !std::filesystem::is_directory(command.seriesRoot)) {
            // A volume file holds one volume; rank 0 may serve it under
            // another id (a teaching session's copy).
            e = catalog.defaultEntry();
        }
        if (e == nullptr) {
            throw LoadError("no series '" + command.seriesId + "' under " + command.seriesRoot);
        }
        if (e->slices.size() != command.slices || e->geometry.dims != command.dims) {
            throw LoadError(command.seriesRoot + ": series '" + command.seriesId + "' has " +
                            std::to_string(e->slices.size()) + " slices here, " +
                            std::to_string(command.slices) +
                            " on rank 0 (every rank needs the same files at the same path)");
        }
        found = *e;
    });
    const RenderDescription d = readFor(command, before);
    auto open = std::make_unique<Open>();
    open->series = command.series;
    open->interpolation = d.sampling.interpolation;
    open->renderer = std::make_unique<DistributedRenderer>(
        comm_,
        loadPart(comm_, entry != nullptr ? *entry : *found, d,
                 splitBrickSize(command.dims, comm_.size(), d.sampling.brickSize)),
        kind_);
    ++reads_;
    open_.push_front(std::move(open));
    return *open_.front();
}

std::string DistributedSeries::backend() const {
    return open_.empty() ? std::string() : open_.front()->renderer->backend();
}

std::string DistributedSeries::device() const {
    return open_.empty() ? std::string() : open_.front()->renderer->device();
}

FrameDetails DistributedSeries::frameDetails() const {
    return open_.empty() ? FrameDetails{} : open_.front()->renderer->frameDetails();
}

} // namespace lucent
