#include "core/fusion/FusionColourMap.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "core/mpr/PlaneSampler.h"

namespace lucent {
namespace {

std::uint8_t clampByte(int v) {
    return static_cast<std::uint8_t>(std::clamp(v, 0, 255));
}

ColourLut makeLut(FusionColourMap map) {
    ColourLut lut{};
    for (int i = 0; i < 256; ++i) {
        int r = i, g = i, b = i;
        switch (map) {
        case FusionColourMap::Grey:
            break;
        case FusionColourMap::HotIron: // black, red, yellow, white
            r = i < 128 ? 2 * i : 255;
            g = i < 128 ? 0 : 2 * (i - 128);
            b = i < 192 ? 0 : 4 * (i - 192);
            break;
        case FusionColourMap::Pet: // black, blue, purple, red, yellow, white
            r = 2 * (i - 63);
            g = i < 64 ? 2 * i : (i < 128 ? 2 * (127 - i) : 2 * (i - 128));
            b = i < 128 ? 2 * i : (i < 192 ? 4 * (191 - i) : 4 * (i - 192));
            break;
        case FusionColourMap::Rainbow: {              // hue 240 (blue) down to 0 (red), full value
            const double h = (255 - i) / 255.0 * 4.0; // 4 = blue ... 0 = red
            const int seg = std::min(3, static_cast<int>(h));
            const int f = static_cast<int>((h - seg) * 255.0 + 0.5);
            const std::array<std::array<int, 3>, 4> ramps{
                {{255, f, 0}, {255 - f, 255, 0}, {0, 255, f}, {0, 255 - f, 255}}};
            r = ramps[seg][0];
            g = ramps[seg][1];
            b = ramps[seg][2];
            break;
        }
        }
        if (i == 255 && map != FusionColourMap::Rainbow) {
            r = g = b = 255;
        }
        lut[i] = {clampByte(r), clampByte(g), clampByte(b)};
    }
    return lut;
}

} // namespace

const char* colourMapName(FusionColourMap map) {
    switch (map) {
    case FusionColourMap::Grey:
        return "grey";
    case FusionColourMap::HotIron:
        return "hot-iron";
    case FusionColourMap::Rainbow:
        return "rainbow";
    case FusionColourMap::Pet:
        return "pet";
    }
    return "grey";
}

const char* colourMapTitle(FusionColourMap map) {
    switch (map) {
    case FusionColourMap::Grey:
        return "Grey";
    case FusionColourMap::HotIron:
        return "Hot iron";
    case FusionColourMap::Rainbow:
        return "Rainbow";
    case FusionColourMap::Pet:
        return "PET";
    }
    return "Grey";
}

std::optional<FusionColourMap> colourMapFromName(std::string_view name) {
    std::string key;
    for (const char c : name) {
        if (c != '-' && c != '_' && c != ' ') {
            key += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        }
    }
    if (key == "grey" || key == "gray") {
        return FusionColourMap::Grey;
    }
    if (key == "hotiron") {
        return FusionColourMap::HotIron;
    }
    if (key == "rainbow") {
        return FusionColourMap::Rainbow;
    }
    if (key == "pet") {
        return FusionColourMap::Pet;
    }
    return std::nullopt;
}

const ColourLut& colourLut(FusionColourMap map) {
    static const std::array<ColourLut, 4> luts{
        makeLut(FusionColourMap::Grey), makeLut(FusionColourMap::HotIron),
        makeLut(FusionColourMap::Rainbow), makeLut(FusionColourMap::Pet)};
    return luts[static_cast<std::size_t>(map)];
}

std::array<std::uint8_t, 3> mapColour(FusionColourMap map, double value, double center,
                                      double width) {
    return colourLut(map)[windowToGrey(value, center, width)];
}

} // namespace lucent
