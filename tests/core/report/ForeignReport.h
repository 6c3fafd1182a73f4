#pragma once
// An SR another program wrote, made with DCMTK's TID 1500 classes: one group
// "Nodule A" with a finding code, a length with its line on `image`
// ((100.5, 200.25) to (140, 180.75) in image coordinates) and a volume, which
// Lucent has no kind for.

#include <QTest>

#include <filesystem>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmsr/cmr/tid1500.h>
#include <dcmtk/dcmsr/codes/dcm.h>
#include <dcmtk/dcmsr/dsrdoc.h>

#include "core/report/ReferencedSeries.h"

namespace lucent::test {

// Returns the SR's SOP Instance UID and series UID, or empty ones on failure.
inline std::pair<std::string, std::string> writeForeignReport(const std::filesystem::path& file,
                                                              const ReferencedSeries& series,
                                                              const ReferencedImage& image) {
    TID1500_MeasurementReport report(CMR_CID7021::ImagingMeasurementReport);
    report.setLanguage(CID5000_Languages::English);
    report.getObservationContext().addPersonObserver("Other^Reader");
    report.addProcedureReported(CMR_CID100::ImagingProcedure);
    report.addIndividualMeasurements();
    auto& group = report.getIndividualMeasurements();
    char uid[100];
    group.setTrackingIdentifier("Nodule A");
    group.setTrackingUniqueIdentifier(dcmGenerateUniqueIdentifier(uid));
    group.setFinding(DSRBasicCodedEntry("M-03010", "SRT", "Nodule"));
    using Value = CMR_TID1501_in_TID1500::MeasurementValue;
    group.addMeasurement(CMR_CID7469::Length, Value("31.5", CMR_CID7181::Millimeter));
    DSRSpatialCoordinatesValue line(DSRTypes::GT_Polyline);
    line.getGraphicDataList().addItem(100.5f, 200.25f);
    line.getGraphicDataList().addItem(140.0f, 180.75f);
    group.getMeasurement().addSpatialCoordinates(
        CODE_DCM_ImageRegion, line,
        DSRImageReferenceValue(image.sopClassUid, image.sopInstanceUid));
    group.addMeasurement(CMR_CID7469::Volume, Value("2.5", CMR_CID7181::CubicCentimeter));
    DSRDocument doc(DSRTypes::DT_Comprehensive3DSR);
    doc.createNewSeriesInStudy(series.studyUid.c_str());
    if (doc.setTreeFromRootTemplate(report).bad()) {
        return {};
    }
    doc.setManufacturer("Other Vendor");
    doc.getCurrentRequestedProcedureEvidence().addItem(
        series.studyUid.c_str(), series.seriesUid.c_str(), image.sopClassUid.c_str(),
        image.sopInstanceUid.c_str());
    DcmFileFormat out;
    if (doc.write(*out.getDataset()).bad() ||
        out.saveFile(file.c_str(), EXS_LittleEndianExplicit).bad()) {
        return {};
    }
    OFString sop, seriesUid;
    doc.getSOPInstanceUID(sop);
    doc.getSeriesInstanceUID(seriesUid);
    return {sop.c_str(), seriesUid.c_str()};
}

} // namespace lucent::test
