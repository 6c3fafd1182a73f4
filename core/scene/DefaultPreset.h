#pragma once

#include <string>
#include <string_view>

#include "core/scene/RenderDescription.h"

namespace lucent {

// The transfer-function preset a volume opens with when none is named, the one
// rule for the CLI, the server and the 3D view: CT gets ct-bone for DVR and
// ct-mip for the projections and the isosurface; everything else mr-default.
inline std::string defaultPresetName(std::string_view modality, RenderMode mode) {
    if (modality != "CT") {
        return "mr-default";
    }
    return mode == RenderMode::Dvr ? "ct-bone" : "ct-mip";
}

} // namespace lucent
