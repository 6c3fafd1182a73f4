#include "core/segmentation/SegmentCodes.h"

#include <algorithm>
#include <array>
#include <cctype>

namespace lucent {
namespace {

const CodedConcept kTissue{"85756007", "SCT", "Tissue"};
const CodedConcept kAnatomy{"123037004", "SCT", "Anatomical Structure"};
const CodedConcept kAltered{"49755003", "SCT", "Morphologically Altered Structure"};

const std::array<SegmentKind, 16> kKinds{{
    {"tissue", kTissue, {"85756007", "SCT", "Tissue"}, 0xb08060},
    {"fat", kTissue, {"55603005", "SCT", "Adipose tissue"}, 0xe6d27a},
    {"muscle", kTissue, {"71616004", "SCT", "Muscle"}, 0xc04040},
    {"bone", kTissue, {"272673000", "SCT", "Bone"}, 0xf1d691},
    {"vessel", kAnatomy, {"59820001", "SCT", "Blood vessel"}, 0xd83a3a},
    {"liver", kAnatomy, {"10200004", "SCT", "Liver"}, 0xdd826f},
    {"spleen", kAnatomy, {"78961009", "SCT", "Spleen"}, 0x9d6a8f},
    {"kidney", kAnatomy, {"64033007", "SCT", "Kidney"}, 0xb9664d},
    {"lung", kAnatomy, {"39607008", "SCT", "Lung"}, 0xc5e4f0},
    {"heart", kAnatomy, {"80891009", "SCT", "Heart"}, 0xce5e4b},
    {"brain", kAnatomy, {"12738006", "SCT", "Brain"}, 0xfad2b4},
    {"skull", kAnatomy, {"89546000", "SCT", "Skull"}, 0xf1d691},
    {"lesion", kAltered, {"52988006", "SCT", "Lesion"}, 0x54d44b},
    {"tumor", kAltered, {"108369006", "SCT", "Neoplasm"}, 0x5ab05a},
    {"cyst", kAltered, {"441457006", "SCT", "Cyst"}, 0x64b4dc},
    {"table",
     {"260787004", "SCT", "Physical object"},
     {"260787004", "SCT", "Physical object"},
     0x808080},
}};

std::string lower(std::string_view s) {
    std::string out(s);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

} // namespace

std::span<const SegmentKind> segmentKinds() {
    return kKinds;
}

const SegmentKind* findSegmentKind(std::string_view name) {
    const std::string key = lower(name);
    for (const SegmentKind& kind : kKinds) {
        if (kind.name == key) {
            return &kind;
        }
    }
    return nullptr;
}

} // namespace lucent
