#include "protocol/MarkMessageJson.h"

#include <cmath>
#include <set>

#include "protocol/JsonFields.h"
#include "protocol/JsonIntegers.h"
#include "protocol/ProtocolError.h"

namespace lucent::remote {
namespace {

using Json = nlohmann::json;

bool isFraction(const Json& v) {
    return v.is_number() && std::isfinite(v.get<double>()) && v.get<double>() >= 0.0 &&
           v.get<double>() <= 1.0;
}

// Code points of valid UTF-8 (nlohmann's parser has checked it).
std::size_t characters(const std::string& text) {
    std::size_t n = 0;
    for (const char c : text) {
        n += (static_cast<unsigned char>(c) & 0xc0u) != 0x80u ? 1 : 0;
    }
    return n;
}

// How many points a mark of this kind has: exactly `min` when min == max.
std::pair<std::size_t, std::size_t> pointCount(MarkKind kind) {
    switch (kind) {
    case MarkKind::Arrow:
    case MarkKind::Circle:
        return {2, 2};
    case MarkKind::Freehand:
        return {2, kMaxFreehandPoints};
    case MarkKind::Text:
        break;
    }
    return {1, 1};
}

std::string countText(MarkKind kind) {
    const auto [lo, hi] = pointCount(kind);
    return lo == hi ? std::to_string(lo) : std::to_string(lo) + " to " + std::to_string(hi);
}

} // namespace

const char* markKindName(MarkKind kind) {
    switch (kind) {
    case MarkKind::Arrow:
        return "arrow";
    case MarkKind::Circle:
        return "circle";
    case MarkKind::Freehand:
        return "freehand";
    case MarkKind::Text:
        break;
    }
    return "text";
}

std::optional<MarkKind> markKindNamed(std::string_view name) {
    for (const MarkKind k :
         {MarkKind::Arrow, MarkKind::Circle, MarkKind::Freehand, MarkKind::Text}) {
        if (name == markKindName(k)) {
            return k;
        }
    }
    return std::nullopt;
}

PointerUpdate parsePointerUpdate(const Json& m) {
    checkKeys(m, "pointer", {"x", "y"});
    if (m.contains("x") != m.contains("y")) {
        throwBadRequest("pointer: give both 'x' and 'y' (or neither, to hide the pointer)");
    }
    if (!m.contains("x")) {
        return {};
    }
    for (const char* key : {"x", "y"}) {
        if (!isFraction(m[key])) {
            throwBadRequest(std::string("pointer: '") + key +
                            "' must be a number from 0 to 1 (a fraction of the view)");
        }
    }
    return {glm::dvec2(m["x"].get<double>(), m["y"].get<double>())};
}

MarkPlace parseMarkPlace(const Json& m) {
    checkKeys(m, "mark", {"kind", "points", "text"});
    const auto kindIt = m.find("kind");
    const auto kind = kindIt != m.end() && kindIt->is_string()
                          ? markKindNamed(kindIt->get<std::string>())
                          : std::nullopt;
    if (!kind) {
        throwBadRequest("mark: 'kind' must be one of arrow, circle, freehand, text");
    }
    MarkPlace place;
    place.kind = *kind;
    const auto points = m.find("points");
    const auto [lo, hi] = pointCount(*kind);
    if (points == m.end() || !points->is_array() || points->size() < lo || points->size() > hi) {
        throwBadRequest(std::string("mark: 'points' must be an array of ") + countText(*kind) +
                        " points for a " + markKindName(*kind) + " mark");
    }
    for (const Json& p : *points) {
        if (!p.is_array() || p.size() != 2 || !isFraction(p[0]) || !isFraction(p[1])) {
            throwBadRequest("mark: each of 'points' must be [x, y], numbers from 0 to 1 "
                            "(fractions of the view)");
        }
        place.points.emplace_back(p[0].get<double>(), p[1].get<double>());
    }
    const auto text = m.find("text");
    if (*kind != MarkKind::Text) {
        if (text != m.end()) {
            throwBadRequest(std::string("mark: 'text' belongs to text marks, not ") +
                            markKindName(*kind));
        }
        return place;
    }
    if (text == m.end() || !text->is_string() || text->get<std::string>().empty() ||
        characters(text->get<std::string>()) > kMaxMarkTextCharacters) {
        throwBadRequest("mark: 'text' must be a string of 1 to " +
                        std::to_string(kMaxMarkTextCharacters) + " characters");
    }
    place.text = text->get<std::string>();
    return place;
}

void writePointerUpdate(Json& m, const PointerUpdate& p) {
    if (p.at) {
        m["x"] = p.at->x;
        m["y"] = p.at->y;
    }
}

void writeMarkPlace(Json& m, const MarkPlace& p) {
    m["kind"] = markKindName(p.kind);
    Json points = Json::array();
    for (const glm::dvec2& q : p.points) {
        points.push_back({q.x, q.y});
    }
    m["points"] = std::move(points);
    if (p.kind == MarkKind::Text) {
        m["text"] = p.text;
    }
}

Json pointerShownJson(const PointerShown& p) {
    Json m{{"type", "pointer"}};
    if (p.at) {
        m["x"] = p.at->x;
        m["y"] = p.at->y;
    }
    return m;
}

Json markShownJson(const MarkShown& s) {
    Json anchors = Json::array();
    for (const glm::dvec3& a : s.anchors) {
        anchors.push_back({a.x, a.y, a.z});
    }
    Json m{{"type", "mark"}, {"id", s.id}, {"kind", markKindName(s.kind)}, {"anchors", anchors}};
    if (s.kind == MarkKind::Text) {
        m["text"] = s.text;
    }
    return m;
}

PointerShown readPointerShown(const Json& m) {
    if (!m.contains("x")) {
        return {};
    }
    return {glm::dvec2(m.at("x").get<double>(), m.at("y").get<double>())};
}

MarkShown readMarkShown(const Json& m) {
    MarkShown s;
    s.id = jsonInteger<std::uint64_t>(m.at("id"), "id");
    const auto kind = markKindNamed(m.at("kind").get<std::string>());
    if (!kind) {
        throw ProtocolError("malformed", "mark: unknown 'kind'", true);
    }
    s.kind = *kind;
    for (const Json& a : m.at("anchors")) {
        if (!a.is_array() || a.size() != 3) {
            throw ProtocolError("malformed", "mark: each anchor must be [x, y, z]", true);
        }
        s.anchors.emplace_back(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
    }
    s.text = m.value("text", std::string());
    return s;
}

} // namespace lucent::remote
