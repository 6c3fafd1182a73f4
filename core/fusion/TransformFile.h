#pragma once
// transform.json, the one reader and writer: what `lucent-cli register` writes and
// `lucent-cli render/convert --transform` read. "matrix" holds 4 rows of 4 numbers
// (row-major) mapping a point in the fixed (base) series' LPS mm to the same anatomy in
// the moving (overlay) series' LPS mm; the other keys are the registration's figures.

#include <optional>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

namespace lucent {

// A transform file that cannot be used: the message names the file and the field.
struct TransformFileError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// What a registration adds to the matrix (all optional in a file that is read).
struct TransformFileFacts {
    std::string metricName; // "mi", "ms"
    double metric = 0.0;
    int iterations = 0;
    double seconds = 0.0;
    bool converged = false;
    std::string reason;
    std::string transform;      // "rigid", "affine" ("" leaves it out)
    std::string initialisation; // where it started ("" leaves it out)
};

// The matrix of `path`. Throws TransformFileError naming the file and what is wrong: it
// cannot be read, is not JSON, has no "matrix", the matrix is not 4 rows of 4 finite
// numbers, its last row is not 0 0 0 1, or it cannot be inverted.
glm::dmat4 readTransformFile(const std::string& path);

// Writes `fixedToMoving` (with the convention and, when given, the facts) to `path`.
// Throws TransformFileError when the file cannot be written.
void writeTransformFile(const std::string& path, const glm::dmat4& fixedToMoving,
                        const std::optional<TransformFileFacts>& facts = std::nullopt);

} // namespace lucent
