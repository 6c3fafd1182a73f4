#pragma once
// What the files of the render options share: the table (RenderOptionTable.cpp),
// the values' text and checks (RenderOptions.cpp) and the Markdown list
// (RenderOptionsMarkdown.cpp). Private to core/scene.

#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene/RenderOptions.h"

namespace lucent::detail {

inline constexpr double kHuge = 1e300;
inline constexpr double kTiny = std::numeric_limits<double>::min(); // a range "above 0"

// The table, made once.
const std::vector<RenderOption>& table();

// The shortest text that reads back as v.
std::string number(double v);
// The whole of `text` as a number; else std::invalid_argument.
double parseNumber(std::string_view text);
// "a, b, c"
std::string choiceText(std::span<const std::string_view> choices);
// "MIN to MAX" of a Number or Integer option ("inf", "0 (exclusive)").
std::string rangeText(const RenderOption& o);
// Throws std::invalid_argument unless v is within the option's range (and whole
// for an Integer).
void checkValue(const RenderOption& o, double v);

} // namespace lucent::detail
