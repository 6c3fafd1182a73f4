#pragma once
// The codes of Lucent's measurement reports, shared by the writer and the reader.
// Private to core/report.

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmsr/dsrcodvl.h>

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

// Other content items.
inline DSRBasicCodedEntry measurementGroupCode() {
    return {"125007", "DCM", "Measurement Group"};
}
inline DSRBasicCodedEntry trackingIdentifierCode() {
    return {"112039", "DCM", "Tracking Identifier"};
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

inline bool sameCode(const DSRCodedEntryValue& a, const DSRBasicCodedEntry& b) {
    return a.getCodeValue() == b.CodeValue &&
           a.getCodingSchemeDesignator() == b.CodingSchemeDesignator;
}

} // namespace lucent::report
