#include "core/scene/RenderDescription.h"

#include "core/scene/RenderOptions.h"

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
    checkRenderOptionRanges(*this); // the ranges of the option table, naming the option
    if (!(camera.fieldOfView > 0.0) || camera.fieldOfView >= 180.0) {
        fail("field of view must lie in (0, 180) degrees");
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
