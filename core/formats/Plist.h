#pragma once

// Internal to core/formats: XML property lists (Apple's plist 1.0), enough for
// InVesalius project files. libplist parses; this turns its nodes into values.

#include <string>
#include <string_view>
#include <vector>

namespace lucent::formats {

struct PlistValue {
    enum class Kind { String, Integer, Real, Bool, Date, Data, Array, Dict };
    Kind kind = Kind::String;
    // A string's text; the decimal literal of an integer or real; "true" or
    // "false"; a date's seconds since 2001-01-01 UTC; the decoded bytes of data.
    std::string text;
    std::vector<PlistValue> items; // array elements, or dict values
    std::vector<std::string> keys; // dict keys, parallel to items

    // The value of a dict entry, or nullptr.
    const PlistValue* find(std::string_view key) const;
    bool isNumber() const { return kind == Kind::Integer || kind == Kind::Real; }
};

// Nesting deeper than this is refused.
inline constexpr int maxPlistDepth = 64;

// Parses a whole XML plist document. Throws std::runtime_error saying what is
// wrong (not well-formed, nesting too deep, a binary plist, ...).
PlistValue parsePlist(std::string_view xml);

} // namespace lucent::formats
