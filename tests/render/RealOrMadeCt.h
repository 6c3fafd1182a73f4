#pragma once
// The real CT where ../shared/data has it, else a made int16 volume of
// blobs with a bright slab: what the GL residency suites render.

#include "tests/core/raycast/RaycastScenes.h"
#include "tests/render/GlTestSupport.h"

namespace lucent::test {

inline Volume realOrMade() {
    if (std::filesystem::exists(philipsCt())) {
        return loadPath(philipsCt());
    }
    return makeVolume(
        {200, 180, 90},
        [](int i, int j, int k) {
            return 8.0 * blobs(i / 5, j / 5, k / 3) - 500.0 + (i > 150 ? 1200.0 : 0.0);
        },
        VoxelType::Int16);
}

} // namespace lucent::test
