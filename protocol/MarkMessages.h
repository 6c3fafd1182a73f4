#pragma once
// Version 4: the presenter's pointer and marks (docs/protocol.md, "Pointer and
// marks"). Small vector messages, never baked into frames: the client sends
// places as fractions of its view; the server sends the pointer as it came
// (screen space) and each mark anchored on the anatomy (LPS mm), which every
// member projects with each frame's `projection`.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace lucent::remote {

// A view holds at most this many marks (until marks-clear or the next open).
inline constexpr std::size_t kMaxMarks = 64;
// A freehand mark has at most this many points.
inline constexpr std::size_t kMaxFreehandPoints = 512;
// A text mark's text: 1 to this many characters (Unicode code points).
inline constexpr std::size_t kMaxMarkTextCharacters = 200;

enum class MarkKind { Arrow, Circle, Freehand, Text };
const char* markKindName(MarkKind kind);
std::optional<MarkKind> markKindNamed(std::string_view name);

// Client: {"type":"pointer","x":0.4,"y":0.6}, fractions of the presenter's view
// ((0, 0) its top-left corner); without x and y the pointer is hidden.
struct PointerUpdate {
    std::optional<glm::dvec2> at;
    bool operator==(const PointerUpdate&) const = default;
};
// Client: a mark. Arrow: tip then tail; circle: centre then a point of its rim;
// freehand: 2 .. kMaxFreehandPoints points; text: one point and `text`.
struct MarkPlace {
    MarkKind kind = MarkKind::Arrow;
    std::vector<glm::dvec2> points; // fractions of the view
    std::string text;               // text marks only
    bool operator==(const MarkPlace&) const = default;
};
struct MarksClear {
    bool operator==(const MarksClear&) const = default;
};

// Server, to every member: where the presenter points (as PointerUpdate).
struct PointerShown {
    std::optional<glm::dvec2> at;
    bool operator==(const PointerShown&) const = default;
};
// Server, to every member: a mark, each point anchored in the patient (LPS mm).
struct MarkShown {
    std::uint64_t id = 0;
    MarkKind kind = MarkKind::Arrow;
    std::vector<glm::dvec3> anchors;
    std::string text;
    bool operator==(const MarkShown&) const = default;
};
struct MarksCleared {
    bool operator==(const MarksCleared&) const = default;
};

} // namespace lucent::remote
