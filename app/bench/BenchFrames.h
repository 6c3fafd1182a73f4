#pragma once
// How the render benchmarks time frames, for lucent-cli bench interactive and tests/perf
// alike: frames turning 5 degrees after one that sets the scene up (upload, compile, caches),
// and the CPU time a frame of a drag takes outside the ray cast.

#include <functional>

#include "core/raycast/CpuRayCaster.h"
#include "core/scene/RenderDescription.h"
#include "render/GpuRayCaster.h"

namespace lucent::bench {

struct TurnFrames {
    double medianMs = 0.0;    // of the turning frames
    double firstMs = 0.0;     // frame 0: the scene set up (not in the median)
    double uploadedMib = 0.0; // over all frames (GL)
    GpuRenderResult first;    // the first turning frame (azimuth 0); .gpu empty for the CPU
};

// One frame of the description's scene, with what it did on the GPU where there is one.
using FrameFunction = std::function<GpuRenderResult(const RenderDescription&)>;

// Frame 0 at azimuth 0, then `turns` frames from azimuth 0 turning 5 degrees each: their
// median, and the first of them kept.
TurnFrames turnFrames(const FrameFunction& render, const RenderDescription& d, int turns = 6);
TurnFrames turnFrames(GpuRayCaster& gpu, const RenderDescription& d, int turns = 6);
TurnFrames turnFrames(CpuRayCaster& cpu, const RenderDescription& d, int turns = 6);

// CPU time of a frame besides its ray cast: the median of 12 frames of a drag turning 3
// degrees each, after one frame that sets the scene up.
struct DragOverhead {
    double outsideCastMs = 0.0; // GL: GpuFrameStats::prepareMs; CPU: outside_cast_ms
    double castMs = 0.0;
    int planned = 0; // GL: frames that planned their bricks anew
};

// `alternate` (not null): the frames swap between it and the description's transfer
// function, both resident before timing, so that each plans anew but uploads nothing.
DragOverhead dragOverhead(GpuRayCaster& gpu, RenderDescription d,
                          const TransferFunction* alternate = nullptr);
// CpuRayCaster::frameDetails' outside_cast_ms and cast_ms, each frame handed back
// (CpuRayCaster::recycle) once shown.
DragOverhead dragOverhead(CpuRayCaster& cpu, RenderDescription d);

} // namespace lucent::bench
