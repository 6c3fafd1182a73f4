#pragma once

#include <string_view>

namespace lucent {

// The GLSL of resources/shaders, compiled into the library (no files to find
// at run time). Throws std::out_of_range for an unknown name.
std::string_view shaderSource(std::string_view fileName);

} // namespace lucent
