# cmake -DIN=file.py -DOUT=file.h -DNAME=kName -P EmbedText.cmake
# Writes a C++ header that holds the text of IN as a raw string literal named NAME (a
# std::string_view), so that a program carries the file with it.
file(READ "${IN}" text)
if(text MATCHES "\\)lucent_text\"")
  message(FATAL_ERROR "${IN} holds the raw string's end marker )lucent_text\"")
endif()
get_filename_component(source "${IN}" NAME)
set(body "// Generated from ${source} by cmake/EmbedText.cmake. Do not edit.\n#pragma once\n\n")
string(APPEND body "#include <string_view>\n\n")
string(APPEND body "inline constexpr std::string_view ${NAME} = R\"lucent_text(${text})lucent_text\";\n")
file(WRITE "${OUT}.tmp" "${body}")
execute_process(COMMAND ${CMAKE_COMMAND} -E copy_if_different "${OUT}.tmp" "${OUT}")
