#include "server/UploadIngest.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>

#include "core/store/StudyStore.h"

namespace lucent::remote {
namespace {

std::string lowerCase(std::string_view text) {
    std::string lower(text);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return lower;
}

std::string_view trimmed(std::string_view text) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) {
        text.remove_prefix(1);
    }
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) {
        text.remove_suffix(1);
    }
    return text;
}

// The media type of a Content-Type value (lower case) and one of its parameters.
std::string mediaType(std::string_view contentType) {
    return lowerCase(trimmed(contentType.substr(0, contentType.find(';'))));
}

std::string parameter(std::string_view contentType, std::string_view name) {
    std::size_t at = contentType.find(';');
    while (at != std::string_view::npos) {
        std::string_view rest = contentType.substr(at + 1);
        const std::size_t next = rest.find(';');
        std::string_view item = trimmed(rest.substr(0, next));
        const std::size_t equals = item.find('=');
        if (equals != std::string_view::npos &&
            lowerCase(trimmed(item.substr(0, equals))) == name) {
            std::string_view value = trimmed(item.substr(equals + 1));
            if (value.size() >= 2 && value.front() == '"' && value.back() == '"') {
                value = value.substr(1, value.size() - 2);
            }
            return std::string(value);
        }
        at = next == std::string_view::npos ? next : at + 1 + next;
    }
    return {};
}

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

std::vector<std::string_view> uploadParts(std::string_view contentType, std::string_view body) {
    const std::string type = mediaType(contentType);
    if (type == "application/dicom") {
        return {body};
    }
    if (type != "multipart/related") {
        throw UploadError(415, "Content-Type '" + std::string(contentType.substr(0, 100)) +
                                   "' is not application/dicom or multipart/related; "
                                   "type=\"application/dicom\"");
    }
    const std::string partType = lowerCase(parameter(contentType, "type"));
    if (!partType.empty() && partType != "application/dicom") {
        throw UploadError(415, "multipart/related: type '" + partType.substr(0, 100) +
                                   "' is not application/dicom");
    }
    const std::string boundary = parameter(contentType, "boundary");
    if (boundary.empty() || boundary.size() > 200) {
        throw UploadError(400, "multipart/related: the Content-Type has no boundary");
    }
    const std::string delimiter = "--" + boundary;
    std::size_t at = body.starts_with(delimiter) ? 0 : body.find("\r\n" + delimiter);
    if (at == std::string_view::npos) {
        throw UploadError(400, "multipart/related: the body holds no boundary '" + boundary + "'");
    }
    at = at == 0 ? delimiter.size() : at + 2 + delimiter.size();
    std::vector<std::string_view> parts;
    while (true) {
        if (body.substr(at).starts_with("--")) {
            break; // the closing delimiter
        }
        const std::size_t headersEnd = body.find("\r\n\r\n", at);
        if (headersEnd == std::string_view::npos) {
            throw UploadError(400, "multipart/related: part " + std::to_string(parts.size() + 1) +
                                       " has no end of its headers");
        }
        const std::string headers = lowerCase(body.substr(at, headersEnd - at));
        const std::size_t typeAt = headers.find("content-type:");
        if (typeAt != std::string::npos) {
            const std::size_t lineEnd = headers.find("\r\n", typeAt);
            const std::string partContentType =
                mediaType(std::string_view(headers).substr(typeAt + 13, lineEnd - typeAt - 13));
            if (partContentType != "application/dicom") {
                throw UploadError(415, "part " + std::to_string(parts.size() + 1) +
                                           ": Content-Type '" + partContentType.substr(0, 100) +
                                           "' is not application/dicom");
            }
        }
        const std::size_t bodyStart = headersEnd + 4;
        const std::size_t next = body.find("\r\n" + delimiter, bodyStart);
        if (next == std::string_view::npos) {
            throw UploadError(400, "multipart/related: part " + std::to_string(parts.size() + 1) +
                                       " is cut short (no closing boundary)");
        }
        parts.push_back(body.substr(bodyStart, next - bodyStart));
        at = next + 2 + delimiter.size();
    }
    if (parts.empty()) {
        throw UploadError(400, "multipart/related: the body holds no part");
    }
    return parts;
}

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
