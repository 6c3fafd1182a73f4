#pragma once
// The codes of Lucent's measurement reports, shared by the writer and the reader.
// Private to core/report.

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmsr/dsrcodvl.h>

#include <string>

namespace lucent::report {

// Concepts of the TID 300 numeric measurements (CID 7469, CID 7464 for statistics).
inline DSRBasicCodedEntry lengthCode() {
    return {"410668003", "SCT", "Length"};
}
inline DSRBasicCodedEntry longAxisCode() {
    return {"103339001", "SCT", "Long Axis"};
}
inline DSRBasicCodedEntry shortAxisCode() {
    return {"103340004", "SCT", "Short Axis"};
}
inline DSRBasicCodedEntry areaCode() {
    return {"42798000", "SCT", "Area"};
}
inline DSRBasicCodedEntry angleCode() {
    return {"1483009", "SCT", "Angle"};
}
inline DSRBasicCodedEntry cobbAngleCode() {
    return {"285285000", "SCT", "Cobb angle"};
}
inline DSRBasicCodedEntry meanCode() {
    return {"373098007", "SCT", "Mean"};
}
inline DSRBasicCodedEntry standardDeviationCode() {
    return {"386136009", "SCT", "Standard Deviation"};
}
inline DSRBasicCodedEntry minimumCode() {
    return {"255605001", "SCT", "Minimum"};
}
inline DSRBasicCodedEntry maximumCode() {
    return {"56851009", "SCT", "Maximum"};
}
// A PET ellipse's SUVs (as TID 1419 and dcmqi write them): the quantity SUVbw, its
// Derivation (TID 300 row 4, CID 7464) Maximum, Mean or Peak Value Within ROI.
inline DSRBasicCodedEntry suvBwCode() {
    return {"126401", "DCM", "SUVbw"};
}
inline DSRBasicCodedEntry derivationCode() {
    return {"121401", "DCM", "Derivation"};
}
inline DSRBasicCodedEntry peakValueWithinRoiCode() {
    return {"126031", "DCM", "Peak Value Within ROI"};
}

// Other content items.
inline DSRBasicCodedEntry measurementGroupCode() {
    return {"125007", "DCM", "Measurement Group"};
}
inline DSRBasicCodedEntry trackingIdentifierCode() {
    return {"112039", "DCM", "Tracking Identifier"};
}
inline DSRBasicCodedEntry trackingUniqueIdentifierCode() {
    return {"112040", "DCM", "Tracking Unique Identifier"};
}
// A lesion's RECIST category (CID 6145 "Baseline Category", PS3.16: "From RECIST"), as a
// qualitative evaluation of its group (TID 1501 row 11).
inline DSRBasicCodedEntry baselineCategoryCode() {
    return {"112016", "DCM", "Baseline Category"};
}
inline DSRBasicCodedEntry targetLesionCode() {
    return {"112074", "DCM", "Target Lesion at Baseline"};
}
inline DSRBasicCodedEntry nonTargetLesionCode() {
    return {"112075", "DCM", "Non-Target Lesion at Baseline"};
}
inline DSRBasicCodedEntry nonLesionCode() {
    return {"112076", "DCM", "Non-Lesion at Baseline"};
}
// A lymph node: Finding Site (TID 1501 row 6) = Lymph node; SRT, the older codes, read too.
inline DSRBasicCodedEntry findingSiteCode() {
    return {"363698007", "SCT", "Finding Site"};
}
inline DSRBasicCodedEntry findingCode() {
    return {"121071", "DCM", "Finding"};
}
inline DSRBasicCodedEntry lymphNodeCode() {
    return {"59441001", "SCT", "Lymph node"};
}
inline bool isFindingSite(const DSRCodedEntryValue& code) {
    return (code.getCodeValue() == "363698007" && code.getCodingSchemeDesignator() == "SCT") ||
           (code.getCodeValue() == "G-C0E3" && code.getCodingSchemeDesignator() == "SRT");
}
inline bool isLymphNode(const DSRCodedEntryValue& code) {
    return (code.getCodeValue() == "59441001" && code.getCodingSchemeDesignator() == "SCT") ||
           (code.getCodeValue() == "T-C4000" && code.getCodingSchemeDesignator() == "SRT");
}
inline DSRBasicCodedEntry imageRegionCode() {
    return {"111030", "DCM", "Image Region"};
}
inline DSRBasicCodedEntry commentCode() {
    return {"121106", "DCM", "Comment"};
}
inline constexpr const char* kPrivateScheme = "99LUCENT";
inline DSRBasicCodedEntry geometryCode() {
    return {"LUCENT-GEOMETRY", kPrivateScheme, "Lucent measurement geometry"};
}

// Units (UCUM).
inline DSRBasicCodedEntry millimetreUnit() {
    return {"mm", "UCUM", "millimeter"};
}
inline DSRBasicCodedEntry degreeUnit() {
    return {"deg", "UCUM", "degree"};
}
inline DSRBasicCodedEntry squareMillimetreUnit() {
    return {"mm2", "UCUM", "square millimeter"};
}
inline DSRBasicCodedEntry hounsfieldUnit() {
    return {"[hnsf'U]", "UCUM", "Hounsfield unit"};
}
inline DSRBasicCodedEntry noUnit() {
    return {"1", "UCUM", "no units"};
}
// SUVbw and Bq/mL as CID 85 and CID 84 name them.
inline DSRBasicCodedEntry suvBwUnit() {
    return {"{SUVbw}g/ml", "UCUM", "Standardized Uptake Value body weight"};
}
inline DSRBasicCodedEntry becquerelPerMillilitreUnit() {
    return {"Bq/ml", "UCUM", "Becquerels/milliliter"};
}
// The UCUM unit of a measurement's statistics (Measurement::unit): HU, SUVbw, Bq/mL, none;
// any other as a UCUM annotation ("{counts}").
inline DSRBasicCodedEntry statisticsUnit(const std::string& unit) {
    if (unit == "HU") {
        return hounsfieldUnit();
    }
    if (unit == "SUVbw") {
        return suvBwUnit();
    }
    if (unit == "Bq/mL") {
        return becquerelPerMillilitreUnit();
    }
    if (unit.empty()) {
        return noUnit();
    }
    return {("{" + unit + "}").c_str(), "UCUM", unit.c_str()};
}

inline bool sameCode(const DSRCodedEntryValue& a, const DSRBasicCodedEntry& b) {
    return a.getCodeValue() == b.CodeValue &&
           a.getCodingSchemeDesignator() == b.CodingSchemeDesignator;
}

} // namespace lucent::report
