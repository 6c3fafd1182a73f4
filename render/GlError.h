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

} // namespace lucent
