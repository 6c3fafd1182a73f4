#include "server/UploadIngest.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include <fstream>
#include <set>

#include "core/store/StudyStore.h"

namespace lucent::remote {
namespace {

std::string partName(std::size_t index, std::size_t count) {
    return count == 1 ? std::string("the upload") : "part " + std::to_string(index + 1);
}

std::string text(DcmItem& d, const DcmTagKey& tag) {
    OFString value;
    d.findAndGetOFStringArray(tag, value);
    return value.c_str();
}

// Temporary files of the store's tmp/, removed unless handed over.
class TemporaryFiles {
public:
    ~TemporaryFiles() {
        for (const auto& path : paths) {
            std::error_code ec;
            std::filesystem::remove(path, ec);
        }
    }
    std::vector<std::filesystem::path> paths;
};

InstanceRecord checkedRecord(const std::filesystem::path& file, const std::string& name) {
    DcmFileFormat format;
    const OFCondition c = format.loadFileUntilTag(file.c_str(), EXS_Unknown, EGL_noChange, 4096,
                                                  ERM_fileOnly, DCM_PixelData);
    if (c.bad()) {
        throw UploadError(400, name + ": the DICOM data cannot be read (" + c.text() + ")");
    }
    DcmDataset& d = *format.getDataset();
    InstanceRecord r;
    r.sopInstanceUid = text(d, DCM_SOPInstanceUID);
    r.series.seriesUid = text(d, DCM_SeriesInstanceUID);
    r.series.studyUid = text(d, DCM_StudyInstanceUID);
    for (const auto& [value, attribute] :
         {std::pair{&r.sopInstanceUid, "SOPInstanceUID (0008,0018)"},
          std::pair{&r.series.studyUid, "StudyInstanceUID (0020,000D)"},
          std::pair{&r.series.seriesUid, "SeriesInstanceUID (0020,000E)"}}) {
        if (value->empty()) {
            throw UploadError(400, name + ": no " + attribute);
        }
    }
    r.series.modality = text(d, DCM_Modality);
    r.series.description = text(d, DCM_SeriesDescription);
    r.series.patientName = text(d, DCM_PatientName);
    r.series.patientId = text(d, DCM_PatientID);
    r.series.studyDate = text(d, DCM_StudyDate);
    r.studyDescription = text(d, DCM_StudyDescription);
    r.accessionNumber = text(d, DCM_AccessionNumber);
    r.patientBirthDate = text(d, DCM_PatientBirthDate);
    Sint32 number = 0;
    d.findAndGetSint32(DCM_SeriesNumber, number);
    r.seriesNumber = number;
    return r;
}

} // namespace

UploadSummary storeUpload(const std::filesystem::path& storeRoot, std::string_view contentType,
                          std::string_view body) {
    const std::vector<std::string_view> parts = uploadParts(contentType, body);
    StudyStore store(storeRoot);
    TemporaryFiles temporary;
    std::vector<InstanceRecord> records;
    // Every part is written and checked before any enters the store.
    for (std::size_t n = 0; n < parts.size(); ++n) {
        const std::string name = partName(n, parts.size());
        const std::string_view part = parts[n];
        if (part.size() < 132 || part.substr(128, 4) != "DICM") {
            throw UploadError(400, name + ": not a DICOM Part 10 file (no 'DICM' at byte 128)");
        }
        temporary.paths.push_back(store.temporaryFile());
        {
            std::ofstream out(temporary.paths.back(), std::ios::binary);
            out.write(part.data(), std::streamsize(part.size()));
            if (!out.flush()) {
                throw StoreError(temporary.paths.back().string() +
                                 ": cannot write an uploaded instance (disk full?)");
            }
        }
        records.push_back(checkedRecord(temporary.paths.back(), name));
    }
    UploadSummary summary;
    std::set<std::string> series;
    StudyStore::Batch batch(store);
    for (std::size_t n = 0; n < records.size(); ++n) {
        (store.add(temporary.paths[n], records[n]) ? summary.stored : summary.alreadyStored) += 1;
        if (series.insert(records[n].series.seriesUid).second) {
            summary.series.push_back(records[n].series.seriesUid);
        }
    }
    temporary.paths.clear(); // moved in, or removed by add()
    return summary;
}

} // namespace lucent::remote
