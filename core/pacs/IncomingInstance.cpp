#include "core/pacs/IncomingInstance_p.h"

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

namespace lucent {
namespace {

std::string text(DcmItem& d, const DcmTagKey& tag) {
    OFString value;
    d.findAndGetOFStringArray(tag, value);
    return value.c_str();
}

} // namespace

bool storeIncoming(DcmDataset& dataset, StudyStore& store) {
    InstanceRecord r;
    r.sopInstanceUid = text(dataset, DCM_SOPInstanceUID);
    r.series.seriesUid = text(dataset, DCM_SeriesInstanceUID);
    r.series.studyUid = text(dataset, DCM_StudyInstanceUID);
    r.series.modality = text(dataset, DCM_Modality);
    r.series.description = text(dataset, DCM_SeriesDescription);
    r.series.patientName = text(dataset, DCM_PatientName);
    r.series.patientId = text(dataset, DCM_PatientID);
    r.series.studyDate = text(dataset, DCM_StudyDate);
    Sint32 number = 0;
    dataset.findAndGetSint32(DCM_SeriesNumber, number);
    r.seriesNumber = number;
    const E_TransferSyntax original = dataset.getOriginalXfer();
    const E_TransferSyntax xfer = original == EXS_Unknown ? EXS_LittleEndianExplicit : original;
    // The dataset, its meta header and preamble: refused before a byte is
    // written when the store's file system cannot take it.
    store.requireSpace(dataset.calcElementLength(xfer, EET_ExplicitLength) + 1024);
    const std::filesystem::path temp = store.temporaryFile();
    DcmFileFormat file(&dataset);
    const OFCondition c = file.saveFile(temp.c_str(), xfer);
    if (c.bad()) {
        std::error_code ec;
        std::filesystem::remove(temp, ec);
        throw store.writeError(temp, temp.string() + ": cannot write a received instance (" +
                                         c.text() + ")");
    }
    return store.add(temp, r);
}

} // namespace lucent
