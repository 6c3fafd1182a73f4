// The render options' values as text: parsing, range checks, the image size
// and the clip box.
#include "core/scene/RenderOptions.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "core/scene/RenderOptions_p.h"

namespace lucent {

using detail::checkValue;
using detail::choiceText;
using detail::number;
using detail::parseNumber;
using detail::table;

// The shortest text that reads back as v.
std::string detail::number(double v) {
    char text[32];
    const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
    return ec == std::errc() ? std::string(text, end) : std::string("?");
}

double detail::parseNumber(std::string_view text) {
    double v = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty()) {
        throw std::invalid_argument("not a number");
    }
    return v;
}

std::string detail::choiceText(std::span<const std::string_view> choices) {
    std::string known;
    for (const std::string_view c : choices) {
        known += (known.empty() ? "" : ", ") + std::string(c);
    }
    return known;
}

std::string detail::rangeText(const RenderOption& o) {
    const auto bound = [](double v) {
        return v >= kHuge    ? std::string("inf")
               : v <= -kHuge ? std::string("-inf")
               : v == kTiny  ? std::string("0 (exclusive)")
                             : number(v);
    };
    return bound(o.min) + " to " + bound(o.max);
}

void detail::checkValue(const RenderOption& o, double v) {
    if (!std::isfinite(v) || v < o.min || v > o.max) {
        throw std::invalid_argument(std::string(o.words) + " " + number(v) + " is out of range (" +
                                    rangeText(o) + ")");
    }
    if (o.kind == OptionKind::Integer && v != std::floor(v)) {
        throw std::invalid_argument(std::string(o.words) + " " + number(v) +
                                    " must be a whole number");
    }
}

std::pair<int, int> parseImageSize(std::string_view text) {
    const std::size_t x = text.find('x');
    int w = 0, h = 0;
    const auto whole = [](std::string_view s, int& out) {
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
        return ec == std::errc() && end == s.data() + s.size() && !s.empty();
    };
    if (x == std::string_view::npos || !whole(text.substr(0, x), w) ||
        !whole(text.substr(x + 1), h)) {
        throw std::invalid_argument("image size '" + std::string(text) + "' is not WIDTHxHEIGHT");
    }
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide) {
        throw std::invalid_argument("image size " + std::string(text) + " is out of range (1 to " +
                                    std::to_string(kMaxImageSide) + " per side)");
    }
    return {w, h};
}

ClipBox parseClipBox(std::string_view text) {
    if (text == "all") {
        return ClipBox{};
    }
    double v[6] = {};
    std::size_t at = 0;
    for (int n = 0; n < 6; ++n) {
        const std::size_t comma = n < 5 ? text.find(',', at) : text.size();
        if (comma == std::string_view::npos) {
            throw std::invalid_argument("clip box '" + std::string(text) +
                                        "' is not X0,Y0,Z0,X1,Y1,Z1 or all");
        }
        try {
            v[n] = parseNumber(text.substr(at, comma - at));
        } catch (const std::invalid_argument&) {
            throw std::invalid_argument("clip box '" + std::string(text) +
                                        "' is not X0,Y0,Z0,X1,Y1,Z1 or all");
        }
        if (!std::isfinite(v[n])) {
            throw std::invalid_argument("clip box '" + std::string(text) + "' is not finite");
        }
        at = comma + 1;
    }
    const ClipBox box{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    if (glm::any(glm::greaterThan(box.lo, box.hi))) {
        throw std::invalid_argument("clip box '" + std::string(text) +
                                    "': a first corner's coordinate exceeds the second's");
    }
    return box;
}

std::string clipBoxText(const ClipBox& box) {
    const ClipBox all;
    if (box.lo == all.lo && box.hi == all.hi) {
        return "all";
    }
    return number(box.lo.x) + "," + number(box.lo.y) + "," + number(box.lo.z) + "," +
           number(box.hi.x) + "," + number(box.hi.y) + "," + number(box.hi.z);
}

std::pair<double, double> parseWindow(std::string_view text) {
    if (text == "auto") {
        return {0.0, 0.0};
    }
    const std::size_t comma = text.find(',');
    const std::string bad = "window '" + std::string(text) +
                            "' is not C,W (a centre and a width "
                            "above 0) or auto";
    if (comma == std::string_view::npos) {
        throw std::invalid_argument(bad);
    }
    double c = 0.0, w = 0.0;
    try {
        c = parseNumber(text.substr(0, comma));
        w = parseNumber(text.substr(comma + 1));
    } catch (const std::invalid_argument&) {
        throw std::invalid_argument(bad);
    }
    if (!std::isfinite(c) || !std::isfinite(w) || !(w > 0.0)) {
        throw std::invalid_argument(bad);
    }
    return {c, w};
}

std::string windowText(double center, double width) {
    return width > 0.0 ? number(center) + "," + number(width) : "auto";
}

void applyRenderOption(RenderDescription& description, const RenderOption& option,
                       std::string_view text) {
    switch (option.kind) {
    case OptionKind::Number:
    case OptionKind::Integer: {
        double v = 0.0;
        try {
            v = parseNumber(text);
        } catch (const std::invalid_argument&) {
            throw std::invalid_argument(std::string(option.name) + ": '" + std::string(text) +
                                        "' is not a number");
        }
        checkValue(option, v);
        break;
    }
    case OptionKind::Choice: {
        bool known = false;
        for (const std::string_view c : option.choices) {
            known = known || c == text;
        }
        if (!known) {
            throw std::invalid_argument(std::string(option.name) + ": '" + std::string(text) +
                                        "' is not one of " + choiceText(option.choices));
        }
        break;
    }
    case OptionKind::Switch:
        if (text != "true" && text != "false") {
            throw std::invalid_argument(std::string(option.name) + ": '" + std::string(text) +
                                        "' is not true or false");
        }
        break;
    case OptionKind::Size:
        parseImageSize(text); // throws with the reason
        break;
    case OptionKind::Box:
        parseClipBox(text); // throws with the reason
        break;
    case OptionKind::Window:
        parseWindow(text); // throws with the reason
        break;
    }
    option.write(description, text);
}

std::string renderOptionValue(const RenderDescription& description, const RenderOption& option) {
    return option.read(description);
}

std::string renderOptionDefault(const RenderOption& option) {
    return option.read(RenderDescription{});
}

void checkRenderOptionRanges(const RenderDescription& d) {
    if (d.width < 1 || d.height < 1 || d.width > kMaxImageSide || d.height > kMaxImageSide) {
        throw std::invalid_argument("image size " + std::to_string(d.width) + "x" +
                                    std::to_string(d.height) + " is out of range (1 to " +
                                    std::to_string(kMaxImageSide) + " per side)");
    }
    for (const RenderOption& o : table()) {
        if (o.kind == OptionKind::Number || o.kind == OptionKind::Integer) {
            const std::string text = o.read(d);
            checkValue(o, parseNumber(text));
        }
    }
}

} // namespace lucent
