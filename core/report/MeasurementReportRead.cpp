// Reading a TID 1500 Measurement Report: DCMTK's document tree walked into
// ReportGroups (core/report/ReportGroup.h), which say what each group shows.
#include <algorithm>
#include <cstdio>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmsr/dsrdoc.h>

#include "core/report/MeasurementReport.h"
#include "core/report/ReportCodes_p.h"
#include "core/report/ReportGroup.h"

namespace lucent {

namespace fs = std::filesystem;
using namespace report;

namespace {

std::string text(DcmItem& d, const DcmTagKey& tag) {
    OFString v;
    return d.findAndGetOFString(tag, v).good() ? std::string(v.c_str()) : std::string();
}

std::string meaningOf(const DSRCodedEntryValue& code) {
    return code.getCodeMeaning().empty() ? code.getCodeValue().c_str()
                                         : code.getCodeMeaning().c_str();
}

ReportRegion::Shape shapeOf(const OFString& graphicType) {
    using S = ReportRegion::Shape;
    if (graphicType == "POINT")
        return S::Point;
    if (graphicType == "POLYLINE")
        return S::Polyline;
    if (graphicType == "POLYGON")
        return S::Polygon;
    if (graphicType == "ELLIPSE")
        return S::Ellipse;
    if (graphicType == "CIRCLE")
        return S::Circle;
    if (graphicType == "MULTIPOINT")
        return S::Multipoint;
    return S::Other;
}

// The region below a NUM: a SCOORD with its IMAGE, or a SCOORD3D. The tree's cursor
// is on the NUM and comes back there.
std::optional<ReportRegion> regionBelow(DSRDocumentTree& tree, const ReferencedSeries* series) {
    if (tree.gotoChild() == 0) {
        return std::nullopt;
    }
    std::optional<ReportRegion> region;
    do {
        DSRContentItem& item = tree.getCurrentContentItem();
        if (item.getValueType() == DSRTypes::VT_SCoord3D && !region) {
            DSRSpatialCoordinates3DValue& s = *item.getSpatialCoordinates3DPtr();
            region = ReportRegion{};
            region->shape = shapeOf(DSRTypes::graphicType3DToEnumeratedValue(s.getGraphicType()));
            for (size_t i = 1; i <= s.getGraphicDataList().getNumberOfItems(); ++i) {
                Float32 x = 0, y = 0, z = 0;
                s.getGraphicDataList().getItem(i, x, y, z);
                region->points.emplace_back(x, y, z);
            }
        } else if (item.getValueType() == DSRTypes::VT_SCoord && !region) {
            DSRSpatialCoordinatesValue& s = *item.getSpatialCoordinatesPtr();
            region = ReportRegion{};
            region->shape = shapeOf(DSRTypes::graphicTypeToEnumeratedValue(s.getGraphicType()));
            std::string sop;
            if (tree.gotoChild() != 0) {
                if (tree.getCurrentContentItem().getValueType() == DSRTypes::VT_Image) {
                    sop = tree.getCurrentContentItem()
                              .getImageReferencePtr()
                              ->getSOPInstanceUID()
                              .c_str();
                }
                tree.gotoParent();
            }
            const ReferencedImage* image = series ? series->find(sop) : nullptr;
            if (image == nullptr) {
                region->unplaced = "on image " + sop + ", not one of the series";
            } else if (image->frames != 1) {
                region->unplaced = "on a frame of the multi-frame image " + sop;
            } else {
                region->imagePlane = image->plane();
                for (size_t i = 1; i <= s.getGraphicDataList().getNumberOfItems(); ++i) {
                    Float32 column = 0, row = 0;
                    s.getGraphicDataList().getItem(i, column, row);
                    region->points.push_back(image->patientPoint({column, row}));
                }
            }
        }
    } while (tree.gotoNext() != 0);
    tree.gotoParent();
    return region;
}

// The code of the Derivation (121401, DCM) below a NUM, or "". The tree's cursor is on the
// NUM and comes back there.
std::string derivationBelow(DSRDocumentTree& tree) {
    if (tree.gotoChild() == 0) {
        return {};
    }
    std::string derivation;
    do {
        DSRContentItem& item = tree.getCurrentContentItem();
        if (item.getValueType() == DSRTypes::VT_Code && item.getCodeValuePtr() != nullptr &&
            sameCode(item.getConceptName(), derivationCode())) {
            derivation = item.getCodeValuePtr()->getCodeValue().c_str();
        }
    } while (derivation.empty() && tree.gotoNext() != 0);
    tree.gotoParent();
    return derivation;
}

std::string describeItem(DSRContentItem& item) {
    std::string out = meaningOf(item.getConceptName());
    const std::string value = item.getStringValue().c_str();
    if (item.getValueType() == DSRTypes::VT_Code && item.getCodeValuePtr() != nullptr) {
        out += " = " + meaningOf(*item.getCodeValuePtr());
    } else if (!value.empty()) {
        out += " = " + value;
    }
    return out.empty() ? std::string(DSRTypes::valueTypeToReadableName(item.getValueType())) : out;
}

// A RECIST category or a lymph node's finding site, read into `lesion`; false for any other
// coded item.
bool lesionItem(const DSRCodedEntryValue& name, const DSRCodedEntryValue& value,
                LesionTracking& lesion) {
    if (sameCode(name, baselineCategoryCode())) {
        if (sameCode(value, targetLesionCode())) {
            lesion.role = LesionRole::Target;
            return true;
        }
        if (sameCode(value, nonTargetLesionCode())) {
            lesion.role = LesionRole::NonTarget;
            return true;
        }
        return sameCode(value, nonLesionCode());
    }
    if ((isFindingSite(name) || sameCode(name, findingCode())) && isLymphNode(value)) {
        lesion.lymphNode = true;
        return true;
    }
    return false;
}

ReportGroup readGroup(DSRDocumentTree& tree, const ReferencedSeries* series) {
    ReportGroup group;
    if (tree.gotoChild() == 0) {
        return group;
    }
    do {
        DSRContentItem& item = tree.getCurrentContentItem();
        const DSRCodedEntryValue& code = item.getConceptName();
        const DSRTypes::E_ValueType type = item.getValueType();
        if (type == DSRTypes::VT_Text && sameCode(code, trackingIdentifierCode())) {
            group.trackingIdentifier = item.getStringValue().c_str();
        } else if (type == DSRTypes::VT_UIDRef && sameCode(code, trackingUniqueIdentifierCode())) {
            group.lesion.trackingUid = item.getStringValue().c_str();
        } else if (type == DSRTypes::VT_Code && item.getCodeValuePtr() != nullptr &&
                   lesionItem(code, *item.getCodeValuePtr(), group.lesion)) {
            // read into group.lesion
        } else if (type == DSRTypes::VT_Text && sameCode(code, commentCode())) {
            group.comment = item.getStringValue().c_str();
        } else if (type == DSRTypes::VT_Text && sameCode(code, geometryCode())) {
            group.geometry = item.getStringValue().c_str();
        } else if (type == DSRTypes::VT_Num && item.getNumericValuePtr() != nullptr) {
            const DSRNumericMeasurementValue& v = *item.getNumericValuePtr();
            ReportNumber n;
            n.code = code.getCodeValue().c_str();
            n.scheme = code.getCodingSchemeDesignator().c_str();
            n.meaning = meaningOf(code);
            Float64 exact = 0.0;
            n.value = v.getFloatingPointRepresentation(exact).good()
                          ? exact
                          : std::strtod(v.getNumericValue().c_str(), nullptr);
            n.unit = v.getMeasurementUnit().getCodeValue().c_str();
            n.region = regionBelow(tree, series);
            n.derivation = derivationBelow(tree);
            group.numbers.push_back(std::move(n));
        } else {
            group.otherItems.push_back(describeItem(item));
        }
    } while (tree.gotoNext() != 0);
    tree.gotoParent();
    return group;
}

// The series the SR refers to: its evidence, then its images' series where known.
std::vector<std::string> referencedSeriesOf(DcmDataset& d) {
    std::vector<std::string> out;
    DcmSequenceOfItems* evidence = nullptr;
    for (const DcmTagKey& tag :
         {DCM_CurrentRequestedProcedureEvidenceSequence, DCM_PertinentOtherEvidenceSequence}) {
        if (d.findAndGetSequence(tag, evidence).bad() || evidence == nullptr) {
            continue;
        }
        for (unsigned long i = 0; i < evidence->card(); ++i) {
            DcmSequenceOfItems* series = nullptr;
            if (evidence->getItem(i)
                    ->findAndGetSequence(DCM_ReferencedSeriesSequence, series)
                    .good() &&
                series != nullptr) {
                for (unsigned long j = 0; j < series->card(); ++j) {
                    const std::string uid = text(*series->getItem(j), DCM_SeriesInstanceUID);
                    if (!uid.empty() && std::find(out.begin(), out.end(), uid) == out.end()) {
                        out.push_back(uid);
                    }
                }
            }
        }
    }
    return out;
}

} // namespace

bool isStructuredReport(const fs::path& file) {
    DcmFileFormat f;
    if (f.loadFile(file.c_str(), EXS_Unknown, EGL_noChange, 256).bad()) {
        return false;
    }
    OFString sopClass;
    f.getDataset()->findAndGetOFString(DCM_SOPClassUID, sopClass);
    return DSRTypes::sopClassUIDToDocumentType(sopClass) != DSRTypes::DT_invalid;
}

ReadReport readMeasurementReport(const fs::path& file, const ReferencedSeries* series) {
    DcmFileFormat f;
    const OFCondition loaded = f.loadFile(file.c_str());
    if (loaded.bad()) {
        throw ReportError(file.string() + ": not a DICOM file (" + loaded.text() + ")");
    }
    DcmDataset& dataset = *f.getDataset();
    const std::string sopClass = text(dataset, DCM_SOPClassUID);
    if (DSRTypes::sopClassUIDToDocumentType(sopClass.c_str()) == DSRTypes::DT_invalid) {
        throw ReportError(file.string() + ": not a structured report (SOP Class UID '" + sopClass +
                          "')");
    }
    f.convertToUTF8(); // labels and texts as Lucent keeps them; unconvertible ones stay as they are
    DSRDocument doc;
    const OFCondition read = doc.read(dataset);
    if (read.bad()) {
        throw ReportError(file.string() + ": an SR that cannot be read (" + read.text() + ")");
    }
    DSRDocumentTree& tree = doc.getTree();
    // TID 1500 by its template identification, or by the usual title where that is missing.
    DcmItem* rootTemplate = nullptr;
    const bool tid1500 =
        (dataset.findAndGetSequenceItem(DCM_ContentTemplateSequence, rootTemplate, 0).good() &&
         rootTemplate != nullptr && text(*rootTemplate, DCM_TemplateIdentifier) == "1500") ||
        (tree.gotoRoot() != 0 &&
         tree.getCurrentContentItem().getConceptName().getCodeValue() == "126000");
    if (!tid1500 || tree.gotoRoot() == 0) {
        throw ReportError(file.string() +
                          ": an SR, but not a TID 1500 Measurement Report (its title is '" +
                          meaningOf(tree.getCurrentContentItem().getConceptName()) + "')");
    }
    ReadReport out;
    out.sopInstanceUid = text(dataset, DCM_SOPInstanceUID);
    out.seriesUid = text(dataset, DCM_SeriesInstanceUID);
    out.studyUid = text(dataset, DCM_StudyInstanceUID);
    out.writtenByLucent = text(dataset, DCM_Manufacturer) == kLucentManufacturer;
    out.referencedSeries = referencedSeriesOf(dataset);

    // Every Measurement Group, wherever it sits below the root.
    std::vector<size_t> groups;
    for (size_t node = tree.gotoRoot(); node != 0; node = tree.iterate()) {
        DSRContentItem& item = tree.getCurrentContentItem();
        if (item.getValueType() == DSRTypes::VT_Container &&
            sameCode(item.getConceptName(), measurementGroupCode())) {
            groups.push_back(node);
        }
    }
    for (const size_t node : groups) {
        tree.gotoNode(node);
        const InterpretedGroup g = interpretGroup(readGroup(tree, series), out.writtenByLucent);
        if (g.measurement) {
            out.measurements.push_back(*g.measurement);
        }
        out.notShown.insert(out.notShown.end(), g.notShown.begin(), g.notShown.end());
    }
    return out;
}

} // namespace lucent
