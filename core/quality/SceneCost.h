#pragma once
// What a render would cost without its accelerations, to set against what it
// took: the samples of a brute-force march (every lattice sample of every ray
// inside the clip box, no leaping, no early termination).

#include <cstddef>

#include "core/scene/RenderDescription.h"

namespace lucent {

std::size_t bruteForceSamples(const RenderDescription& description);

} // namespace lucent
