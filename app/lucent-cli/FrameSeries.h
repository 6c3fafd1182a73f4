#pragma once
// render --repeat N, local or distributed: N frames turning the azimuth 5
// degrees each, and the timing head of the --stats line.

#include <QString>

#include <vector>

#include "core/scene/Renderer.h"

namespace lucent::cli {

struct FrameSeries {
    RenderResult first;        // the first frame, written as the PNG
    std::vector<double> ms;    // each frame's time
    FrameDetails firstDetails; // the renderer's figures after the first frame
    FrameDetails lastDetails;  // and after the last (steady state)
};

// Frames after the first are handed back (Renderer::recycle) once timed, as
// the workstation's 3D view does.
FrameSeries renderFrames(Renderer& renderer, RenderDescription description, int repeat);

// "load_ms=.. [first_ms=..] render_ms=<median of the rest> samples=.. bricks_total=..
// bricks_used=.. lod=.." of the first frame.
QString seriesStats(double loadMs, const FrameSeries& series);

} // namespace lucent::cli
