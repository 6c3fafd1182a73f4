#pragma once
// The pointer and marks a teaching session's server sends (protocol version 4,
// docs/protocol.md "Pointer and marks"), as a client keeps them to draw over
// its frames: marks by id, anchored in the patient, and the pointer in
// fractions of the view.

#include <cstdint>
#include <map>
#include <optional>

#include <glm/glm.hpp>

#include "protocol/ServerMessages.h"

namespace lucent {

class TeachingMarks {
public:
    // pointer, mark, marks-cleared: applied, true; false for other messages.
    bool apply(const remote::ServerMessage& message);
    void clear();

    const std::map<std::uint64_t, remote::MarkShown>& marks() const { return marks_; }
    const std::optional<glm::dvec2>& pointer() const { return pointer_; }

private:
    std::map<std::uint64_t, remote::MarkShown> marks_;
    std::optional<glm::dvec2> pointer_;
};

} // namespace lucent
