#pragma once
// The colour maps of a fused overlay: grey, hot iron and PET (DICOM PS3.6 Annex B's
// well-known palettes 1.2.840.10008.1.5.1 and .2, as linear segments) and rainbow (blue
// to red through cyan, green and yellow). 256 entries each, indexed by the overlay's
// window as windowToGrey indexes grey.

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

namespace lucent {

enum class FusionColourMap { Grey, HotIron, Rainbow, Pet };

inline constexpr std::array kFusionColourMaps{FusionColourMap::Grey, FusionColourMap::HotIron,
                                              FusionColourMap::Rainbow, FusionColourMap::Pet};

using ColourLut = std::array<std::array<std::uint8_t, 3>, 256>;

// "grey", "hot-iron", "rainbow", "pet": the names of the CLI and saved settings.
const char* colourMapName(FusionColourMap map);
// "Grey", "Hot iron", "Rainbow", "PET": what a menu shows.
const char* colourMapTitle(FusionColourMap map);
// From a name (case-insensitive; "hotiron", "hot_iron" and "gray" too); nullopt otherwise.
std::optional<FusionColourMap> colourMapFromName(std::string_view name);

const ColourLut& colourLut(FusionColourMap map);

// The colour of `value` under the window (center, width): the LUT entry windowToGrey
// picks. NaN gives entry 0.
std::array<std::uint8_t, 3> mapColour(FusionColourMap map, double value, double center,
                                      double width);

} // namespace lucent
