#pragma once
// A render description as JSON text, exact (numbers in the shortest form that
// reads back to the same double): what rank 0 of a distributed render server
// sends the other ranks for every frame. The volume is not part of it.

#include <string>
#include <string_view>

#include "core/scene/RenderDescription.h"

namespace lucent {

// Every option of the render options table (the clip box among them), the
// transfer function, the field of view, the background and the SIMD switch.
std::string toJson(const RenderDescription& description);

// The description toJson() wrote (volume null). Throws std::invalid_argument
// naming the field that is missing or malformed.
RenderDescription parseRenderDescription(std::string_view json);

} // namespace lucent
