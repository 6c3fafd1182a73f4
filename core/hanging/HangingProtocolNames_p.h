#pragma once
// Private to core/hanging: the names of enum values in protocol files.

#include <array>
#include <cctype>
#include <optional>
#include <string>
#include <string_view>

#include "core/hanging/HangingProtocol.h"

namespace lucent {

template <typename Enum> struct NamedValue {
    std::string_view name;
    Enum value;
};

inline constexpr std::array<NamedValue<ViewportView>, 6> kViewNames{{
    {"axial", ViewportView::Axial},
    {"coronal", ViewportView::Coronal},
    {"sagittal", ViewportView::Sagittal},
    {"oblique", ViewportView::Oblique},
    {"3d", ViewportView::Volume3D},
    {"stack", ViewportView::Stack},
}};

inline constexpr std::array<NamedValue<SliceOrientation>, 4> kOrientationNames{{
    {"axial", SliceOrientation::Axial},
    {"coronal", SliceOrientation::Coronal},
    {"sagittal", SliceOrientation::Sagittal},
    {"oblique", SliceOrientation::Oblique},
}};

// The words of seriesKindName (core/io, another library).
inline constexpr std::array<NamedValue<SeriesKind>, 3> kKindNames{{
    {"volume", SeriesKind::Volume},
    {"localizer", SeriesKind::Localizer},
    {"image", SeriesKind::Image},
}};

inline bool equalNoCase(std::string_view a, std::string_view b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) ==
                      std::tolower(static_cast<unsigned char>(y));
           });
}

template <typename Enum, std::size_t N>
std::optional<Enum> valueOf(std::string_view text, const std::array<NamedValue<Enum>, N>& names) {
    for (const auto& n : names) {
        if (equalNoCase(n.name, text)) {
            return n.value;
        }
    }
    return std::nullopt;
}

template <typename Enum, std::size_t N>
std::string_view nameOf(Enum value, const std::array<NamedValue<Enum>, N>& names) {
    for (const auto& n : names) {
        if (n.value == value) {
            return n.name;
        }
    }
    return "?";
}

template <typename Enum, std::size_t N>
std::string listOf(const std::array<NamedValue<Enum>, N>& names) {
    std::string list;
    for (const auto& n : names) {
        list += (list.empty() ? "" : ", ") + std::string(n.name);
    }
    return list;
}

} // namespace lucent
