#pragma once
// What a part of a volume (a rank of a distributed render) changes in a GPU
// render; nothing for a whole volume. Private to render/.

#include <optional>

#include "core/scene/RenderDescription.h"
#include "core/volume/VolumePart.h"

namespace lucent {

// The description in the part's indices, the whole volume's box that anchors
// the lattice, the open faces, the description's clip box.
struct PartFrame {
    RenderDescription local;
    glm::dvec3 boxLo{0.0}, boxHi{0.0};
    glm::ivec3 openHi{0};
    glm::dvec3 sceneClipLo{0.0}, sceneClipHi{0.0};
    bool empty = false; // the clip box leaves the part nothing
};

PartFrame partFrame(const std::optional<VolumePart>& part, const Volume& volume,
                    const RenderDescription& asked);

} // namespace lucent
