#include "core/scene/RenderDescription.h"

#include "core/mpr/PlaneSampler.h"
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
    if (overlay.volume != nullptr) {
        const Volume& o = *overlay.volume;
        if (o.empty() || o.type() != VoxelType::Float32) {
            fail("the overlay must be a non-empty Float32 volume on the base's grid "
                 "(resampleOverlay)");
        }
        if (volume != nullptr && o.dims() != volume->dims()) {
            const auto text = [](glm::ivec3 d) {
                return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
            };
            fail("the overlay's grid " + text(o.dims()) + " is not the volume's " +
                 text(volume->dims()) + " (resample it onto the volume's grid first)");
        }
        if (!(overlay.style.width > 0.0) || !std::isfinite(overlay.style.center)) {
            fail("overlay window: a centre and a width above 0 are needed (auto is resolved "
                 "by resolveOverlayWindow)");
        }
        if (mode == RenderMode::Isosurface) {
            fail("an overlay is drawn in dvr, mip, minip and avg modes, not iso");
        }
    }
}

void resolveOverlayWindow(RenderOverlay& overlay) {
    if (overlay.volume == nullptr || overlay.style.width > 0.0) {
        return;
    }
    const WindowLevel w = defaultWindow(*overlay.volume);
    overlay.style.center = w.center;
    overlay.style.width = w.width;
}

} // namespace lucent
