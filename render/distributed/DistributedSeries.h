#pragma once
// The series a distributed render server has open over all its ranks
// (docs/distributed.md), each with its DistributedRenderer: the last two used,
// as the one-process server keeps two. Rank 0 leads (it serves the clients and
// broadcasts a command for every frame); the other ranks follow. Every rank
// carries out the same commands in the same order, so every rank makes the
// same choice (open a series, read it again with a wider halo, forget the
// oldest) without another word.

#include <cstdint>
#include <list>
#include <memory>
#include <string>

#include "core/scene/Renderer.h"
#include "render/RenderDevice.h"
#include "render/distributed/Communicator.h"
#include "render/distributed/RankCommand.h"

namespace lucent {

class DistributedRenderer;

class DistributedSeries {
public:
    // `comm` must outlive it. Each rank renders on the CPU or with GL (`kind`).
    DistributedSeries(const Communicator& comm, RendererKind kind);
    ~DistributedSeries();
    DistributedSeries(const DistributedSeries&) = delete;
    DistributedSeries& operator=(const DistributedSeries&) = delete;

    // Rank 0: has every rank render `command`'s frame of `entry` (the entry
    // rank 0 serves; the others find it under command.seriesRoot) and renders
    // its own part. The composited frame. Throws DistributedError naming the
    // ranks that failed (every rank learns of it and goes on following),
    // std::invalid_argument for a description out of range.
    RenderResult lead(const RankCommand& command, const SeriesEntry& entry);
    // Rank 0: the other ranks stop following.
    void release();
    // The other ranks: carry out rank 0's commands until it releases them.
    // A failure every rank learns of ends that frame, not the loop.
    void follow();

    // The ranks' backend and device, once a series is open ("" before).
    std::string backend() const;
    std::string device() const;
    // The last frame's figures (DistributedRenderer::frameDetails()).
    FrameDetails frameDetails() const;
    // Times a series was read (opened or read again): for the tests.
    int reads() const { return reads_; }

private:
    struct Open;
    RenderResult carryOut(const RankCommand& command, const SeriesEntry* entry);
    Open& opened(const RankCommand& command, const SeriesEntry* entry);

    const Communicator& comm_;
    RendererKind kind_;
    std::list<std::unique_ptr<Open>> open_; // most recently used first
    bool released_ = false;
    int reads_ = 0;
};

} // namespace lucent
