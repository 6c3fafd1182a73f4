# cmake -DOUT=file.cpp -DINPUTS="a.vert;b.frag" -P EmbedShaders.cmake
# Writes a C++ source that holds each shader's text, looked up by file name.
set(body "// Generated from resources/shaders by cmake/EmbedShaders.cmake. Do not edit.\n")
string(APPEND body "#include \"render/ShaderSources.h\"\n\n#include <stdexcept>\n#include <string>\n\n")
string(APPEND body "namespace lucent {\n\nstd::string_view shaderSource(std::string_view name) {\n")
foreach(input IN LISTS INPUTS)
  get_filename_component(name "${input}" NAME)
  file(READ "${input}" text)
  string(APPEND body "    if (name == \"${name}\") {\n        return R\"lucent_glsl(${text})lucent_glsl\";\n    }\n")
endforeach()
string(APPEND body "    throw std::out_of_range(\"no shader named \" + std::string(name));\n}\n\n} // namespace lucent\n")
file(WRITE "${OUT}.tmp" "${body}")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different "${OUT}.tmp" "${OUT}")
