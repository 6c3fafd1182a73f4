# LUCENT_FUZZ=ON: the libFuzzer build (fuzz/, packaging/fuzz.sh). Clang only.
# Every library is instrumented for coverage and built with AddressSanitizer
# and UndefinedBehaviorSanitizer (any UB aborts, so it counts as a crash); the
# harnesses link libFuzzer's driver. Only the libraries the harnesses need are
# built: no GUI, no app, no test suites.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "LUCENT_FUZZ needs clang (libFuzzer), not ${CMAKE_CXX_COMPILER_ID}: "
                      "CC=clang-14 CXX=clang++-14 cmake -S . -B build-fuzz -DLUCENT_FUZZ=ON "
                      "(packaging/install-deps.sh installs clang and libfuzzer-14-dev)")
endif()
if(LUCENT_SANITIZE)
  message(FATAL_ERROR "LUCENT_FUZZ brings its own sanitizers; leave LUCENT_SANITIZE off")
endif()
set(LUCENT_BUILD_TESTS OFF CACHE BOOL "Build the test suites" FORCE)
set(LUCENT_BUILD_GUI OFF CACHE BOOL "Build the Qt Widgets workstation" FORCE)

set(lucent_fuzz_sanitizers -fsanitize=address,undefined -fno-sanitize-recover=all
                           -fno-omit-frame-pointer -g)
# The marching-cubes table (core/surface) is computed at compile time: more
# steps than clang allows by default (GCC's limit is far higher).
add_compile_options(-fsanitize=fuzzer-no-link ${lucent_fuzz_sanitizers} -fconstexpr-steps=100000000)
add_link_options(-fsanitize=address,undefined)
