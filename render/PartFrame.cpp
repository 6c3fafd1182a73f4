#include "render/PartFrame_p.h"

namespace lucent {

PartFrame partFrame(const std::optional<VolumePart>& part, const Volume& volume,
                    const RenderDescription& asked) {
    PartFrame f{asked};
    f.boxHi = glm::dvec3(volume.dims() - 1);
    if (!part) {
        return f;
    }
    const glm::dvec3 offset(part->offset), wholeHi(part->whole.dims - 1);
    f.boxLo = -offset;
    f.boxHi = wholeHi - offset;
    f.sceneClipLo = glm::max(asked.clip.lo, glm::dvec3(0.0)) - offset;
    f.sceneClipHi = glm::min(asked.clip.hi, wholeHi) - offset;
    f.local.clip.lo = glm::max(f.sceneClipLo, glm::dvec3(part->owned.lo) - offset);
    f.local.clip.hi = glm::min(f.sceneClipHi, glm::dvec3(part->owned.hi) - offset);
    f.local.background = glm::dvec3(0.0);
    f.local.volume = &volume;
    for (int a = 0; a < 3; ++a) {
        f.openHi[a] = part->sharedHi(a) && asked.clip.hi[a] >= double(part->owned.hi[a]) ? 1 : 0;
    }
    f.empty = glm::any(glm::lessThan(f.local.clip.hi, f.local.clip.lo));
    return f;
}

} // namespace lucent
