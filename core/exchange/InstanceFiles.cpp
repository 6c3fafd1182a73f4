#include "core/exchange/InstanceFiles.h"

#include <algorithm>
#include <mutex>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcmetinf.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/oflog/oflog.h>

namespace lucent {
namespace {

// Reading up to the pixel data is what the sender wants: DCMTK's note that it
// stopped there is not for the user.
void quietDcmdata() {
    static std::once_flag once;
    std::call_once(
        once, [] { OFLog::getLogger("dcmtk.dcmdata").setLogLevel(OFLogger::ERROR_LOG_LEVEL); });
}

std::string stringOf(DcmItem& item, const DcmTagKey& tag) {
    OFString v;
    return item.findAndGetOFString(tag, v).good() ? std::string(v.c_str()) : std::string();
}

} // namespace

InstanceHeader readInstanceHeader(const std::filesystem::path& file) {
    quietDcmdata();
    DcmFileFormat format;
    const OFCondition c = format.loadFileUntilTag(file.c_str(), EXS_Unknown, EGL_noChange,
                                                  DCM_MaxReadLength, ERM_fileOnly, DCM_PixelData);
    if (c.bad()) {
        throw InstanceFileError(file.string() + ": not a DICOM file (" + c.text() + ")");
    }
    InstanceHeader h;
    h.file = file;
    DcmMetaInfo& meta = *format.getMetaInfo();
    DcmDataset& data = *format.getDataset();
    h.sopClassUid = stringOf(meta, DCM_MediaStorageSOPClassUID);
    h.sopInstanceUid = stringOf(meta, DCM_MediaStorageSOPInstanceUID);
    h.transferSyntaxUid = stringOf(meta, DCM_TransferSyntaxUID);
    if (h.sopClassUid.empty()) {
        h.sopClassUid = stringOf(data, DCM_SOPClassUID);
    }
    if (h.sopInstanceUid.empty()) {
        h.sopInstanceUid = stringOf(data, DCM_SOPInstanceUID);
    }
    h.studyUid = stringOf(data, DCM_StudyInstanceUID);
    h.seriesUid = stringOf(data, DCM_SeriesInstanceUID);
    const char* missing = h.sopClassUid.empty()      ? "SOP Class UID"
                          : h.sopInstanceUid.empty() ? "SOP Instance UID"
                          : h.transferSyntaxUid.empty()
                              ? "Transfer Syntax UID (no file meta header)"
                              : nullptr;
    if (missing) {
        throw InstanceFileError(file.string() + ": no " + missing + ": not a DICOM instance");
    }
    return h;
}

std::vector<InstanceHeader> collectInstances(const std::filesystem::path& path,
                                             const std::string& seriesUid,
                                             std::vector<std::string>& passedOver) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(path, ec)) {
        throw InstanceFileError(path.string() + ": no such file or folder");
    }
    std::vector<fs::path> files;
    if (fs::is_directory(path, ec)) {
        for (const auto& entry : fs::recursive_directory_iterator(path, ec)) {
            if (entry.is_regular_file()) {
                files.push_back(entry.path());
            }
        }
        std::sort(files.begin(), files.end());
    } else {
        files.push_back(path);
    }
    std::vector<InstanceHeader> out;
    for (const fs::path& f : files) {
        try {
            InstanceHeader h = readInstanceHeader(f);
            if (h.sopClassUid == UID_MediaStorageDirectoryStorage) {
                passedOver.push_back(f.string() + ": a DICOMDIR, not an instance");
            } else if (seriesUid.empty() || h.seriesUid == seriesUid) {
                out.push_back(std::move(h));
            }
        } catch (const InstanceFileError& e) {
            passedOver.push_back(e.what());
        }
    }
    return out;
}

} // namespace lucent
