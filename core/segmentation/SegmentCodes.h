#pragma once
// What a segment is, in the words DICOM SEG uses: a category and a type, each a SNOMED CT
// concept (PS3.16 CID 7150 and 7151 draw from them), from a small built-in table.

#include <span>
#include <string>
#include <string_view>

namespace lucent {

struct CodedConcept {
    std::string value;          // "10200004"
    std::string scheme = "SCT"; // SNOMED CT
    std::string meaning;        // "Liver"
    bool operator==(const CodedConcept&) const = default;
};

struct SegmentKind {
    std::string_view name; // "liver", as a user or the CLI names it
    CodedConcept category;
    CodedConcept type;
    unsigned colour; // 0xRRGGBB, what a new segment of this kind is drawn in
};

// Tissue, organs, bone, vessel, lesion, ...: the table the Segments panel offers.
std::span<const SegmentKind> segmentKinds();
// By name (case-insensitive); nullptr when the table has none.
const SegmentKind* findSegmentKind(std::string_view name);

} // namespace lucent
