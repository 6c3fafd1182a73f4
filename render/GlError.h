#pragma once

#include <stdexcept>
#include <string>

namespace lucent {

// Anything the GL path cannot do: no context, GL too old, a shader that does
// not compile, an allocation the driver refuses. The message says which.
class GlError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The driver refused memory (GL_OUT_OF_MEMORY): the caller may retry smaller.
class GlOutOfMemory : public GlError {
public:
    using GlError::GlError;
};

} // namespace lucent
