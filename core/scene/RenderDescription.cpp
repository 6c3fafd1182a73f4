#include "core/scene/RenderDescription.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace lucent {

const char* renderModeName(RenderMode mode) {
    switch (mode) {
    case RenderMode::Dvr:
        return "dvr";
    case RenderMode::Mip:
        return "mip";
    case RenderMode::MinIp:
        return "minip";
    case RenderMode::Average:
        return "avg";
    case RenderMode::Isosurface:
        return "iso";
    }
    return "?";
}

const char* interpolationName(Interpolation interp) {
    switch (interp) {
    case Interpolation::Nearest:
        return "nearest";
    case Interpolation::Linear:
        return "linear";
    case Interpolation::Cubic:
        return "cubic";
    }
    return "?";
}

void RenderDescription::validate() const {
    auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
    constexpr int kMaxSize = 16384;
    if (width < 1 || height < 1 || width > kMaxSize || height > kMaxSize) {
        fail("image size " + std::to_string(width) + "x" + std::to_string(height) +
             " is out of range (1 to " + std::to_string(kMaxSize) + " per side)");
    }
    if (!(sampling.step > 0.0) || !std::isfinite(sampling.step) || sampling.step < 1e-4) {
        fail("step " + std::to_string(sampling.step) +
             " must be a positive number of voxels (at least 0.0001)");
    }
    if (!(sampling.earlyTermination > 0.0) || sampling.earlyTermination > 1.0) {
        fail("early termination threshold must lie in (0, 1]");
    }
    if (sampling.brickSize < 1) {
        fail("brick size must be at least 1");
    }
    if (!(camera.zoom > 0.0) || !std::isfinite(camera.zoom)) {
        fail("zoom must be a positive number");
    }
    if (!(camera.fieldOfView > 0.0) || camera.fieldOfView >= 180.0) {
        fail("field of view must lie in (0, 180) degrees");
    }
    if (!std::isfinite(camera.azimuth) || !std::isfinite(camera.elevation) ||
        !std::isfinite(isoValue)) {
        fail("azimuth, elevation and iso value must be finite");
    }
    if (!(camera.distance >= 0.0) || !std::isfinite(camera.distance)) {
        fail("camera distance must be 0 (fit the volume) or a positive number of mm");
    }
    if (!std::isfinite(camera.panRight) || !std::isfinite(camera.panUp)) {
        fail("camera pan must be finite");
    }
    if (sampling.classification == Classification::Pre &&
        sampling.interpolation == Interpolation::Cubic) {
        fail("pre-classification is available with nearest and linear interpolation, not cubic");
    }
    if (volume != nullptr && volume->empty()) {
        fail("the volume is empty");
    }
    transferFunction.validate();
}

} // namespace lucent
