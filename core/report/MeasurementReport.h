#pragma once
// Measurements as a DICOM Comprehensive 3D SR Measurement Report (TID 1500),
// written and read with DCMTK's dcmsr (private to lucent_report).
//
// Each measurement is one Measurement Group (TID 1501): its label as the Tracking
// Identifier, its lesion's tracking UID (a new one when it has none) as the Tracking Unique
// Identifier, a RECIST target or non-target lesion as the qualitative evaluation
// (112016, DCM, "Baseline Category") = (112074, DCM, "Target Lesion at Baseline") or
// (112075, DCM, "Non-Target Lesion at Baseline") (CID 6145), a lymph node as Finding Site
// (363698007, SCT) = (59441001, SCT, "Lymph node"); all of them read back from any SR
// (the SRT codes of finding site and lymph node too). Its values as TID 300 numeric measurements
// (UCUM mm, deg, mm2 and [hnsf'U]), an arrow's text as a TEXT item. Its points go as SCOORD on the
// image of an acquired slice when they all lie on one (with that image's reference), else as
// SCOORD3D in patient mm with the series' Frame of Reference. Because both keep coordinates in
// 32-bit floats, Lucent also stores each measurement's exact points, plane and statistics in a TEXT
// item with the private code (LUCENT-GEOMETRY, 99LUCENT): its own SRs read back exactly, and other
// readers list that item as one they do not know. Lucent's SRs carry Manufacturer "Lucent".

#include <filesystem>
#include <string>
#include <vector>

#include "core/measure/Measurement.h"
#include "core/report/ReferencedSeries.h"

namespace lucent {

inline constexpr const char* kLucentManufacturer = "Lucent";

struct ReportIdentity {
    std::string seriesUid;   // of the SR's series; empty: a new one
    int seriesNumber = 9900; // where a study browser lists it
    std::string softwareVersion = "Lucent";
};

struct WrittenReport {
    std::string sopInstanceUid;
    std::string seriesUid;
    std::string studyUid;
};

// Writes the measurements of `series` (read-only ones and incomplete ones are left
// out) as a new SR instance at `file`, the study and patient taken from the
// series' first image. Throws ReportError naming the file or the measurement.
WrittenReport writeMeasurementReport(const std::filesystem::path& file,
                                     const ReferencedSeries& series,
                                     const std::vector<Measurement>& measurements,
                                     const ReportIdentity& identity = {});

struct ReadReport {
    std::string sopInstanceUid;
    std::string seriesUid;
    std::string studyUid;
    bool writtenByLucent = false;
    std::vector<std::string> referencedSeries; // from the evidence and the image references
    std::vector<Measurement> measurements;     // read-only unless Lucent wrote them
    std::vector<std::string> notShown;         // content items Lucent cannot show, in words
};

// Reads an SR. `series` (may be null) gives the planes of referenced images, needed
// to place the SCOORD of SRs Lucent did not write. Throws ReportError naming the
// file when it is not DICOM, not an SR, or not a TID 1500 Measurement Report.
ReadReport readMeasurementReport(const std::filesystem::path& file,
                                 const ReferencedSeries* series = nullptr);

// A new DICOM UID (DCMTK's generator under its site root): a new lesion's tracking UID.
std::string newDicomUid();

// True when the file is an SR document (its SOP class), without reading its content.
bool isStructuredReport(const std::filesystem::path& file);

} // namespace lucent
