#include "core/formats/Plist.h"

#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <stdexcept>

#include <plist/plist.h>

namespace lucent::formats {

namespace {

struct PlistFree {
    void operator()(void* node) const { plist_free(static_cast<plist_t>(node)); }
};
using PlistPtr = std::unique_ptr<void, PlistFree>;

// Memory libplist hands over (dict keys, iterators).
struct CFree {
    void operator()(void* p) const { std::free(p); }
};

[[noreturn]] void fail(const std::string& what) {
    throw std::runtime_error(what);
}

std::string realText(double v) {
    char buffer[64];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
    return ec == std::errc() ? std::string(buffer, end) : std::string("nan");
}

PlistValue convert(plist_t node, int depth);

PlistValue array(plist_t node, int depth) {
    PlistValue v;
    v.kind = PlistValue::Kind::Array;
    const std::uint32_t n = plist_array_get_size(node);
    v.items.reserve(n);
    for (std::uint32_t i = 0; i < n; ++i) {
        v.items.push_back(convert(plist_array_get_item(node, i), depth + 1));
    }
    return v;
}

PlistValue dict(plist_t node, int depth) {
    PlistValue v;
    v.kind = PlistValue::Kind::Dict;
    plist_dict_iter raw = nullptr;
    plist_dict_new_iter(node, &raw);
    const std::unique_ptr<void, CFree> iter(raw);
    for (;;) {
        char* rawKey = nullptr;
        plist_t item = nullptr;
        plist_dict_next_item(node, raw, &rawKey, &item);
        const std::unique_ptr<char, CFree> key(rawKey);
        if (!item) {
            return v;
        }
        v.keys.emplace_back(key ? key.get() : "");
        v.items.push_back(convert(item, depth + 1));
    }
}

PlistValue convert(plist_t node, int depth) {
    if (depth > maxPlistDepth) {
        fail("nesting deeper than " + std::to_string(maxPlistDepth) + " levels");
    }
    using K = PlistValue::Kind;
    PlistValue v;
    switch (plist_get_node_type(node)) {
    case PLIST_DICT:
        return dict(node, depth);
    case PLIST_ARRAY:
        return array(node, depth);
    case PLIST_STRING: {
        std::uint64_t length = 0;
        const char* text = plist_get_string_ptr(node, &length);
        v.kind = K::String;
        v.text = text ? std::string(text, static_cast<std::size_t>(length)) : std::string();
        return v;
    }
    case PLIST_UINT: { // libplist 2.2 keeps a negative integer as its two's complement
        std::uint64_t bits = 0;
        plist_get_uint_val(node, &bits);
        v.kind = K::Integer;
        v.text = bits > std::uint64_t{std::numeric_limits<std::int64_t>::max()}
                     ? std::to_string(static_cast<std::int64_t>(bits))
                     : std::to_string(bits);
        return v;
    }
    case PLIST_REAL: {
        double value = 0.0;
        plist_get_real_val(node, &value);
        v.kind = K::Real;
        v.text = realText(value);
        return v;
    }
    case PLIST_BOOLEAN: {
        std::uint8_t value = 0;
        plist_get_bool_val(node, &value);
        v.kind = K::Bool;
        v.text = value ? "true" : "false";
        return v;
    }
    case PLIST_DATE: {
        std::int32_t seconds = 0;
        std::int32_t micro = 0;
        plist_get_date_val(node, &seconds, &micro);
        v.kind = K::Date;
        v.text = realText(seconds + micro * 1e-6);
        return v;
    }
    case PLIST_DATA: {
        std::uint64_t length = 0;
        const char* bytes = plist_get_data_ptr(node, &length);
        v.kind = K::Data;
        v.text = bytes ? std::string(bytes, static_cast<std::size_t>(length)) : std::string();
        return v;
    }
    default:
        fail("an element that is not a plist value (uid or key)");
    }
}

} // namespace

const PlistValue* PlistValue::find(std::string_view key) const {
    if (kind != Kind::Dict) {
        return nullptr;
    }
    for (std::size_t i = 0; i < keys.size(); ++i) {
        if (keys[i] == key) {
            return &items[i];
        }
    }
    return nullptr;
}

PlistValue parsePlist(std::string_view xml) {
    if (xml.size() > std::numeric_limits<std::uint32_t>::max()) {
        fail("too large (" + std::to_string(xml.size()) + " bytes)");
    }
    if (plist_is_binary(xml.data(), static_cast<std::uint32_t>(xml.size()))) {
        fail("a binary plist, not an XML one");
    }
    // libplist reads up to the given length; the copy also ends in a NUL.
    const std::string text(xml);
    plist_t raw = nullptr;
    plist_from_xml(text.c_str(), static_cast<std::uint32_t>(text.size()), &raw);
    const PlistPtr root(raw);
    if (!root) {
        fail("not a well-formed XML property list (an unknown element, a tag left open, "
             "bad nesting or no <plist> value)");
    }
    return convert(root.get(), 0);
}

} // namespace lucent::formats
