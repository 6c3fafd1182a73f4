#pragma once
// The camera turned about the patient's head-foot axis: the turntable of movies and the
// rotating MIP of the 3D view (the classic PET cine). Plain C++.

#include "core/scene/Camera.h"

namespace lucent {

// Frame k of `frames` turns the start's azimuth by k * degrees / frames (about the
// head-foot axis, the view's up axis at elevation 0): a full turn loops without a repeat.
Camera turntableCamera(const Camera& start, double degrees, int frames, int k);

// The rotating MIP: a full turn in kRotatingMipFrames frames, one every
// kRotatingMipFrameMs (10 degrees a frame, 3.6 s a turn).
inline constexpr int kRotatingMipFrames = 36;
inline constexpr int kRotatingMipFrameMs = 100;

// The rotating MIP's camera after `frame` frames: the start levelled (elevation 0) and
// centred (no pan), its zoom, distance and field of view kept, turned about the head-foot
// axis by frame * 360 / kRotatingMipFrames degrees; the azimuth in [0, 360).
Camera rotatingMipCamera(const Camera& start, int frame);

} // namespace lucent
