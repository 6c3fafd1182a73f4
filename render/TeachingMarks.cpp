#include "render/TeachingMarks.h"

namespace lucent {

bool TeachingMarks::apply(const remote::ServerMessage& message) {
    if (const auto* pointer = std::get_if<remote::PointerShown>(&message)) {
        pointer_ = pointer->at;
    } else if (const auto* mark = std::get_if<remote::MarkShown>(&message)) {
        marks_[mark->id] = *mark;
    } else if (std::holds_alternative<remote::MarksCleared>(message)) {
        marks_.clear();
    } else {
        return false;
    }
    return true;
}

void TeachingMarks::clear() {
    marks_.clear();
    pointer_.reset();
}

} // namespace lucent
