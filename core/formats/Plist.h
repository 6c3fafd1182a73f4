#pragma once

// Internal to core/formats: a small, strict reader of XML property lists
// (Apple's plist 1.0), enough for InVesalius project files.

#include <string>
#include <string_view>
#include <vector>

namespace lucent::formats {

struct PlistValue {
    enum class Kind { String, Integer, Real, Bool, Date, Data, Array, Dict };
    Kind kind = Kind::String;
    std::string text; // string, date or data text; the literal of integer, real and bool
    std::vector<PlistValue> items; // array elements, or dict values
    std::vector<std::string> keys; // dict keys, parallel to items

    // The value of a dict entry, or nullptr.
    const PlistValue* find(std::string_view key) const;
    bool isNumber() const { return kind == Kind::Integer || kind == Kind::Real; }
};

// Parses a whole plist document. Throws std::runtime_error saying what is wrong
// and at which line.
PlistValue parsePlist(std::string_view xml);

} // namespace lucent::formats
