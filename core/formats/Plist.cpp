#include "core/formats/Plist.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <stdexcept>

namespace lucent::formats {

namespace {

class Parser {
public:
    explicit Parser(std::string_view xml) : s_(xml) {}

    PlistValue document() {
        skipMisc();
        if (peekTag() == "?xml") {
            skipPast("?>");
            skipMisc();
        }
        if (s_.substr(pos_).starts_with("<!DOCTYPE")) {
            skipPast(">");
            skipMisc();
        }
        const auto [name, selfClosing] = openTag();
        if (name != "plist" || selfClosing) {
            fail("expected <plist>");
        }
        PlistValue root = value(0);
        closeTag("plist");
        skipMisc();
        if (pos_ != s_.size()) {
            fail("unexpected content after </plist>");
        }
        return root;
    }

private:
    [[noreturn]] void fail(const std::string& what) const {
        const auto line = 1 + std::count(s_.begin(), s_.begin() + static_cast<long>(pos_), '\n');
        throw std::runtime_error("plist line " + std::to_string(line) + ": " + what);
    }

    void skipSpace() {
        while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) {
            ++pos_;
        }
    }
    void skipPast(std::string_view end) {
        const std::size_t at = s_.find(end, pos_);
        if (at == std::string_view::npos) {
            fail("unterminated markup (missing '" + std::string(end) + "')");
        }
        pos_ = at + end.size();
    }
    void skipMisc() { // whitespace and comments
        for (;;) {
            skipSpace();
            if (!s_.substr(pos_).starts_with("<!--")) {
                return;
            }
            skipPast("-->");
        }
    }
    std::string_view peekTag() const {
        if (pos_ >= s_.size() || s_[pos_] != '<') {
            return {};
        }
        std::size_t end = pos_ + 1;
        while (end < s_.size() && !std::isspace(static_cast<unsigned char>(s_[end])) &&
               s_[end] != '>' && s_[end] != '/') {
            ++end;
        }
        return s_.substr(pos_ + 1, end - pos_ - 1);
    }
    // Reads <name attr...> or <name/>; returns the name and whether it closed itself.
    std::pair<std::string, bool> openTag() {
        skipMisc();
        const std::string_view name = peekTag();
        if (name.empty() || name.front() == '/') {
            fail("expected an element");
        }
        const std::size_t close = s_.find('>', pos_);
        if (close == std::string_view::npos) {
            fail("unterminated tag <" + std::string(name) + ">");
        }
        const bool selfClosing = s_[close - 1] == '/';
        pos_ = close + 1;
        return {std::string(name), selfClosing};
    }
    void closeTag(std::string_view name) {
        skipMisc();
        const std::string expected = "</" + std::string(name) + ">";
        if (!s_.substr(pos_).starts_with(expected)) {
            fail("expected " + expected);
        }
        pos_ += expected.size();
    }
    // Character data up to the next '<', with entities decoded.
    std::string textUntilTag() {
        const std::size_t end = s_.find('<', pos_);
        if (end == std::string_view::npos) {
            fail("unterminated text");
        }
        std::string out;
        for (std::size_t i = pos_; i < end; ++i) {
            if (s_[i] != '&') {
                out += s_[i];
                continue;
            }
            const std::size_t semi = s_.find(';', i);
            if (semi == std::string_view::npos || semi > end) {
                pos_ = i;
                fail("bad entity");
            }
            const std::string_view e = s_.substr(i + 1, semi - i - 1);
            if (e == "lt") {
                out += '<';
            } else if (e == "gt") {
                out += '>';
            } else if (e == "amp") {
                out += '&';
            } else if (e == "quot") {
                out += '"';
            } else if (e == "apos") {
                out += '\'';
            } else if (e.starts_with('#')) {
                const bool hex = e.size() > 1 && (e[1] == 'x' || e[1] == 'X');
                const std::string digits(e.substr(hex ? 2 : 1));
                const unsigned long c = std::strtoul(digits.c_str(), nullptr, hex ? 16 : 10);
                out += c < 0x80 ? static_cast<char>(c) : '?'; // non-ASCII: not needed here
            } else {
                pos_ = i;
                fail("unknown entity &" + std::string(e) + ";");
            }
            i = semi;
        }
        pos_ = end;
        return out;
    }

    PlistValue value(int depth) {
        if (depth > 64) {
            fail("nesting too deep");
        }
        const auto [name, selfClosing] = openTag();
        PlistValue v;
        using K = PlistValue::Kind;
        if (name == "dict" || name == "array") {
            v.kind = name == "dict" ? K::Dict : K::Array;
            if (selfClosing) {
                return v;
            }
            for (;;) {
                skipMisc();
                if (s_.substr(pos_).starts_with("</")) {
                    break;
                }
                if (v.kind == K::Dict) {
                    const auto [keyTag, keyEmpty] = openTag();
                    if (keyTag != "key") {
                        fail("expected <key> in <dict>, found <" + keyTag + ">");
                    }
                    v.keys.push_back(keyEmpty ? std::string() : textUntilTag());
                    if (!keyEmpty) {
                        closeTag("key");
                    }
                }
                v.items.push_back(value(depth + 1));
            }
            closeTag(name);
            return v;
        }
        if (name == "true" || name == "false") {
            if (!selfClosing) {
                closeTag(name);
            }
            v.kind = K::Bool;
            v.text = name;
            return v;
        }
        if (name == "string") {
            v.kind = K::String;
        } else if (name == "integer") {
            v.kind = K::Integer;
        } else if (name == "real") {
            v.kind = K::Real;
        } else if (name == "date") {
            v.kind = K::Date;
        } else if (name == "data") {
            v.kind = K::Data;
        } else {
            fail("unknown element <" + name + ">");
        }
        if (!selfClosing) {
            v.text = textUntilTag();
            closeTag(name);
        }
        return v;
    }

    std::string_view s_;
    std::size_t pos_ = 0;
};

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
    return Parser(xml).document();
}

} // namespace lucent::formats
