// Writing measurements as a TID 1500 Measurement Report with DCMTK's TID classes,
// plus the items those classes have no call for (SCOORD3D, Lucent's geometry).
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>
#include <system_error>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmsr/cmr/tid1500.h>
#include <dcmtk/dcmsr/dsrdoc.h>

#include "core/report/MeasurementGeometryText.h"
#include "core/report/MeasurementReport.h"
#include "core/report/ReportCodes_p.h"

namespace lucent {

namespace fs = std::filesystem;
using namespace report;
using Group = CMR_TID1501_in_TID1500;
using NumericValue = Group::MeasurementValue;

namespace {

void check(const OFCondition& c, const fs::path& file, const std::string& what) {
    if (c.bad()) {
        throw ReportError(file.string() + ": " + what + ": " + c.text());
    }
}

std::string newUid() {
    return newDicomUid();
}

// A DS string (at most 16 characters) as close to v as fits, and v itself as the
// numeric value's floating point representation: read back exactly.
NumericValue numeric(double v, const DSRBasicCodedEntry& unit) {
    char text[32];
    for (int digits = 15; digits > 0; --digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, v);
        if (std::string(text).size() <= 16) {
            break;
        }
    }
    NumericValue value(text, CMR_CID7181(DSRCodedEntryValue(unit)), OFFalse);
    value.setFloatingPointRepresentation(v);
    return value;
}

struct Value {
    DSRBasicCodedEntry code;
    double value = 0.0;
    DSRBasicCodedEntry unit;
    std::vector<int> region; // indices of the points of its image region; empty: none
    DSRTypes::E_GraphicType graphic = DSRTypes::GT_Polyline;
    DSRTypes::E_GraphicType3D graphic3d = DSRTypes::GT3_Polyline;
    std::optional<DSRBasicCodedEntry> derivation{}; // TID 300 row 4 (the SUVs)
};

// SUVmax, SUVmean and SUVpeak: the quantity SUVbw with its derivation, in {SUVbw}g/ml.
void addSuvValues(const Measurement& m, std::vector<Value>& out) {
    if (!m.suv) {
        return;
    }
    const std::pair<DSRBasicCodedEntry, double> suvs[] = {{maximumCode(), m.suv->max},
                                                          {meanCode(), m.suv->mean},
                                                          {peakValueWithinRoiCode(), m.suv->peak}};
    for (const auto& [derivation, v] : suvs) {
        if (std::isfinite(v)) {
            out.push_back({suvBwCode(),
                           v,
                           suvBwUnit(),
                           {},
                           DSRTypes::GT_Polyline,
                           DSRTypes::GT3_Polyline,
                           derivation});
        }
    }
}

std::vector<Value> valuesOf(const Measurement& m) {
    const auto line = [](std::vector<int> points) { return points; };
    switch (m.kind) {
    case MeasurementKind::Distance:
    case MeasurementKind::Arrow:
        return {{lengthCode(), measurementLengthMm(m), millimetreUnit(), line({0, 1})}};
    case MeasurementKind::Angle:
        return {{angleCode(), measurementAngleDegrees(m), degreeUnit(), line({0, 1, 2})}};
    case MeasurementKind::CobbAngle:
        return {{cobbAngleCode(), measurementAngleDegrees(m), degreeUnit(), line({0, 1, 2, 3})}};
    case MeasurementKind::Bidirectional:
        return {{longAxisCode(), bidirectionalLongAxisMm(m), millimetreUnit(), line({0, 1})},
                {shortAxisCode(), bidirectionalShortAxisMm(m), millimetreUnit(), line({2, 3})}};
    case MeasurementKind::Ellipse: {
        // DICOM's ELLIPSE: the major axis first.
        const EllipseRoi e = measurementEllipse(m);
        std::vector<int> axes = e.radiusU >= e.radiusV ? line({0, 1, 2, 3}) : line({2, 3, 0, 1});
        std::vector<Value> out{{areaCode(), m.statistics.areaMm2, squareMillimetreUnit(), axes,
                                DSRTypes::GT_Ellipse, DSRTypes::GT3_Ellipse}};
        const DSRBasicCodedEntry unit = statisticsUnit(m.unit);
        const RoiStatistics& s = m.statistics;
        const std::pair<DSRBasicCodedEntry, double> stats[] = {
            {meanCode(), s.mean},
            {standardDeviationCode(), s.standardDeviation},
            {minimumCode(), s.minimum},
            {maximumCode(), s.maximum}};
        for (const auto& [code, v] : stats) {
            if (std::isfinite(v)) {
                out.push_back({code, v, unit, {}});
            }
        }
        addSuvValues(m, out);
        return out;
    }
    }
    return {};
}

void addRegion(Group& group, const Value& value, const Measurement& m, const ReferencedImage* image,
               const std::string& frameOfReference, const fs::path& file) {
    if (value.region.empty()) {
        return;
    }
    Group::TID300_Measurement& num = group.getMeasurement();
    if (image != nullptr) {
        DSRSpatialCoordinatesValue scoord(value.graphic);
        for (const int i : value.region) {
            const glm::dvec2 c = image->imageCoordinates(m.points[static_cast<std::size_t>(i)]);
            scoord.getGraphicDataList().addItem(static_cast<Float32>(c.x),
                                                static_cast<Float32>(c.y));
        }
        check(num.addSpatialCoordinates(
                  imageRegionCode(), scoord,
                  DSRImageReferenceValue(image->sopClassUid, image->sopInstanceUid)),
              file, "image region of " + std::string(measurementKindName(m.kind)));
        return;
    }
    DSRSpatialCoordinates3DValue scoord3d(value.graphic3d);
    scoord3d.setFrameOfReferenceUID(frameOfReference.c_str());
    for (const int i : value.region) {
        const glm::dvec3& p = m.points[static_cast<std::size_t>(i)];
        scoord3d.getGraphicDataList().addItem(static_cast<Float32>(p.x), static_cast<Float32>(p.y),
                                              static_cast<Float32>(p.z));
    }
    // TID 300 has no call for a 3D region: an extra item below the measurement.
    num.gotoRoot();
    check(num.addExtraContentItem(DSRTypes::RT_inferredFrom, DSRTypes::VT_SCoord3D,
                                  DSRTypes::AM_belowCurrent),
          file, "3D image region");
    check(num.getCurrentContentItem().setConceptName(imageRegionCode()), file, "3D image region");
    check(num.getCurrentContentItem().setSpatialCoordinates3D(scoord3d), file,
          "3D image region of " + std::string(measurementKindName(m.kind)));
}

void addGroup(CMR_TID1500& report, const Measurement& m, const ReferencedSeries& series,
              std::set<const ReferencedImage*>& referenced, const fs::path& file) {
    const std::string what = measurementKindName(m.kind);
    check(report.addIndividualMeasurements(), file, "measurement group");
    Group& group = report.getIndividualMeasurements();
    check(group.setTrackingIdentifier(m.label.empty() ? what : m.label), file,
          what + ": tracking identifier");
    const std::string trackingUid = m.lesion.trackingUid.empty() ? newUid() : m.lesion.trackingUid;
    check(group.setTrackingUniqueIdentifier(trackingUid.c_str()), file,
          what + ": tracking UID '" + trackingUid + "'");
    if (m.lesion.lymphNode) {
        check(group.addFindingSite(DSRCodedEntryValue(lymphNodeCode())), file,
              what + ": finding site");
    }
    const ReferencedImage* image = series.acquiredImageOf(m);
    if (image == nullptr && series.frameOfReferenceUid.empty()) {
        throw ReportError(file.string() + ": " + what +
                          " lies on an oblique plane, and the series has no Frame of Reference "
                          "UID for its 3D coordinates");
    }
    if (image != nullptr) {
        referenced.insert(image);
    }
    for (const Value& v : valuesOf(m)) {
        check(group.addMeasurement(CMR_CID7469(DSRCodedEntryValue(v.code)),
                                   numeric(v.value, v.unit), OFTrue, OFFalse),
              file, what + ": " + v.code.CodeMeaning.c_str());
        if (v.derivation) {
            check(group.getMeasurement().setDerivation(
                      CMR_CID7464(DSRCodedEntryValue(*v.derivation))),
                  file, what + ": derivation " + v.derivation->CodeMeaning.c_str());
        }
        addRegion(group, v, m, image, series.frameOfReferenceUid, file);
    }
    if (m.lesion.role != LesionRole::None) {
        const DSRBasicCodedEntry category =
            m.lesion.role == LesionRole::Target ? targetLesionCode() : nonTargetLesionCode();
        check(group.addQualitativeEvaluation(DSRCodedEntryValue(baselineCategoryCode()),
                                             DSRCodedEntryValue(category)),
              file, what + ": lesion category");
    }
    const auto addText = [&](const DSRBasicCodedEntry& code, const std::string& text) {
        group.gotoRoot();
        check(group.addExtraContentItem(DSRTypes::RT_contains, DSRTypes::VT_Text,
                                        DSRTypes::AM_belowCurrent),
              file, what + ": text item");
        check(group.getCurrentContentItem().setConceptName(code), file, what + ": text item");
        check(group.getCurrentContentItem().setStringValue(text.c_str()), file,
              what + ": text item");
    };
    if (m.kind == MeasurementKind::Arrow && !m.text.empty()) {
        addText(commentCode(), m.text);
    }
    addText(geometryCode(), encodeMeasurementGeometry(m));
}

// The SR of `format` written to `file` whole or not at all. The temporary name keeps
// the target's as its start: a study store's temporary file names its writer's
// process, and the store keeps such files while that process runs.
void saveWhole(DcmFileFormat& format, const fs::path& file) {
    const fs::path temp = file.parent_path() / (file.filename().string() + ".part");
    const OFCondition c = format.saveFile(temp.c_str(), EXS_LittleEndianExplicit);
    std::error_code ec;
    if (c.bad()) {
        fs::remove(temp, ec);
        throw ReportError(file.string() + ": cannot write the SR (" + c.text() + ")");
    }
    fs::rename(temp, file, ec);
    if (ec) {
        fs::remove(temp, ec);
        throw ReportError(file.string() + ": cannot write the SR (" + ec.message() + ")");
    }
}

} // namespace

std::string newDicomUid() {
    char buffer[100];
    return dcmGenerateUniqueIdentifier(buffer, SITE_INSTANCE_UID_ROOT);
}

WrittenReport writeMeasurementReport(const fs::path& file, const ReferencedSeries& series,
                                     const std::vector<Measurement>& measurements,
                                     const ReportIdentity& identity) {
    if (series.images.empty()) {
        throw ReportError(file.string() + ": the series has no image to refer to");
    }
    DcmFileFormat first;
    const fs::path& firstFile = series.images.front().file;
    if (first.loadFile(firstFile.c_str(), EXS_Unknown, EGL_noChange, 4096).bad()) {
        throw ReportError(firstFile.string() + ": cannot read the series' first image");
    }

    CMR_TID1500 report(CMR_CID7021::ImagingMeasurementReport);
    check(report.setLanguage(CID5000_Languages::English), file, "language");
    check(report.getObservationContext().addDeviceObserver(newUid(), "Lucent", kLucentManufacturer),
          file, "observer");
    check(report.addProcedureReported(CMR_CID100::ImagingProcedure), file, "procedure");
    std::set<const ReferencedImage*> referenced;
    for (const Measurement& m : measurements) {
        if (!m.readOnly && m.complete()) {
            addGroup(report, m, series, referenced, file);
        }
    }
    if (!report.getImageLibrary().hasImageLibrary()) {
        check(report.getImageLibrary().createNewImageLibrary(), file, "image library");
    }
    if (!referenced.empty()) {
        check(report.getImageLibrary().addImageGroup(), file, "image library");
        for (const ReferencedImage* image : referenced) {
            DcmFileFormat header;
            if (header.loadFile(image->file.c_str(), EXS_Unknown, EGL_noChange, 4096).bad()) {
                throw ReportError(image->file.string() + ": cannot read the image's header");
            }
            check(report.getImageLibrary().addImageEntry(*header.getDataset(),
                                                         TID1600_ImageLibrary::withAllDescriptors),
                  file, "image library entry " + image->sopInstanceUid);
        }
    }

    DSRDocument doc(DSRTypes::DT_Comprehensive3DSR);
    // Lucent's texts (labels, arrow texts) are UTF-8: so is the whole SR.
    check(first.convertToUTF8(), file, "character set of " + firstFile.string());
    check(doc.readStudyData(*first.getDataset()), file, "study of " + firstFile.string());
    check(doc.setSpecificCharacterSetType(DSRTypes::CS_UTF8), file, "character set");
    check(doc.createNewSeriesInStudy(series.studyUid.c_str()), file, "series");
    check(doc.setTreeFromRootTemplate(report), file, "TID 1500 content");
    // The template's tree is an Enhanced SR, which has no SCOORD3D.
    check(doc.changeDocumentType(DSRTypes::DT_Comprehensive3DSR), file, "document type");
    check(doc.setManufacturer(kLucentManufacturer), file, "manufacturer");
    check(doc.setManufacturerModelName("Lucent"), file, "model");
    check(doc.setSoftwareVersions(identity.softwareVersion.c_str()), file, "software");
    check(doc.setSeriesDescription("Lucent measurements"), file, "series description");
    check(doc.setSeriesNumber(std::to_string(identity.seriesNumber).c_str()), file,
          "series number");
    check(doc.setInstanceNumber("1"), file, "instance number");
    check(doc.getCodingSchemeIdentification().addItem(kPrivateScheme, "", "Lucent private codes",
                                                      "Lucent"),
          file, "coding scheme");
    for (const ReferencedImage& image : series.images) {
        check(doc.getCurrentRequestedProcedureEvidence().addItem(
                  series.studyUid.c_str(), series.seriesUid.c_str(), image.sopClassUid.c_str(),
                  image.sopInstanceUid.c_str()),
              file, "evidence " + image.sopInstanceUid);
    }

    DcmFileFormat out;
    DcmDataset& dataset = *out.getDataset();
    check(doc.write(dataset), file, "SR document");
    if (!identity.seriesUid.empty()) {
        check(dataset.putAndInsertString(DCM_SeriesInstanceUID, identity.seriesUid.c_str()), file,
              "series UID");
    }
    saveWhole(out, file);
    WrittenReport written;
    OFString value;
    dataset.findAndGetOFString(DCM_SOPInstanceUID, value);
    written.sopInstanceUid = value.c_str();
    dataset.findAndGetOFString(DCM_SeriesInstanceUID, value);
    written.seriesUid = value.c_str();
    written.studyUid = series.studyUid;
    return written;
}

} // namespace lucent
