#include "core/exchange/DicomExport.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>
#include <random>

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcddirif.h>

#include "core/dicom/Deidentifier.h"
#include "core/exchange/ZipWriter.h"

namespace lucent {
namespace {

namespace fs = std::filesystem;

// A path that is removed, with all below it, unless kept.
class StagingPath {
public:
    explicit StagingPath(fs::path p) : path_(std::move(p)) {}
    ~StagingPath() {
        if (!kept_) {
            std::error_code ec;
            fs::remove_all(path_, ec);
        }
    }
    StagingPath(const StagingPath&) = delete;
    StagingPath& operator=(const StagingPath&) = delete;
    const fs::path& path() const { return path_; }
    void keep() { kept_ = true; }

private:
    fs::path path_;
    bool kept_ = false;
};

bool isInside(const fs::path& path, const fs::path& folder) {
    const fs::path p = fs::weakly_canonical(path);
    const fs::path f = fs::weakly_canonical(folder);
    const auto [end, _] = std::mismatch(f.begin(), f.end(), p.begin(), p.end());
    return end == f.end();
}

// A hidden sibling of `output` that no other export picks.
fs::path siblingOf(const fs::path& output, const char* suffix) {
    std::random_device random;
    char tag[16];
    std::snprintf(tag, sizeof tag, "%08x", random());
    return output.parent_path() / ("." + output.filename().string() + ".partial-" + tag + suffix);
}

void checkOutput(const std::vector<InstanceHeader>& instances, const fs::path& output) {
    std::error_code ec;
    if (fs::exists(output, ec)) {
        throw ExportError(output.string() + ": exists already (an export never overwrites)");
    }
    if (!fs::is_directory(output.parent_path(), ec)) {
        throw ExportError(output.string() + ": its folder " + output.parent_path().string() +
                          " does not exist");
    }
    for (const InstanceHeader& h : instances) {
        if (isInside(output, h.file.parent_path())) {
            throw ExportError(output.string() + ": lies inside the source folder " +
                              h.file.parent_path().string() +
                              " (an export never writes into its source)");
        }
    }
}

// DICOM/STnnnn/SEnnnn/IMnnnnnn: studies and series numbered in order of appearance.
std::vector<std::string> fileIdsOf(const std::vector<InstanceHeader>& instances) {
    std::map<std::string, int> studies;
    std::map<std::string, std::pair<int, int>> series; // study number, series number
    std::map<int, int> seriesInStudy, imagesInSeries;
    std::vector<std::string> ids;
    for (const InstanceHeader& h : instances) {
        const int st = studies.try_emplace(h.studyUid, int(studies.size()) + 1).first->second;
        auto [it, added] = series.try_emplace(h.studyUid + "|" + h.seriesUid, st, 0);
        if (added) {
            it->second.second = ++seriesInStudy[st];
        }
        const int se = it->second.second;
        const int im = ++imagesInSeries[st * 10000 + se];
        char id[40];
        std::snprintf(id, sizeof id, "DICOM/ST%04d/SE%04d/IM%06d", st, se, im);
        ids.emplace_back(id);
    }
    return ids;
}

void writeDicomdir(const fs::path& root, const std::vector<std::string>& fileIds) {
    const fs::path path = root / "DICOMDIR";
    DicomDirInterface dir;
    dir.enableInventMode(OFTrue); // de-identified files lack type 1 record keys
    auto check = [&](const OFCondition& c, const std::string& what) {
        if (c.bad()) {
            throw ExportError(path.string() + ": " + what + " (" + c.text() + ")");
        }
    };
    check(dir.createNewDicomDir(DicomDirInterface::AP_GeneralPurposeMIME, path.c_str()),
          "cannot create the DICOMDIR");
    for (const std::string& id : fileIds) {
        check(dir.addDicomFile(id.c_str(), root.c_str()), "cannot list " + id);
    }
    check(dir.writeDicomDir(), "cannot write the DICOMDIR");
}

} // namespace

ExportResult exportInstances(const std::vector<InstanceHeader>& instances,
                             const fs::path& outputPath, const ExportOptions& options) {
    if (instances.empty()) {
        throw ExportError(outputPath.string() + ": nothing to export");
    }
    const fs::path output = fs::absolute(outputPath).lexically_normal();
    std::string extension = output.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    ExportResult result{output, 0, extension == ".zip", {}};
    checkOutput(instances, output);

    StagingPath staging(siblingOf(output, ""));
    std::error_code ec;
    if (!fs::create_directory(staging.path(), ec)) {
        throw ExportError(output.string() + ": cannot write in " + output.parent_path().string() +
                          " (" + ec.message() + ")");
    }
    const std::vector<std::string> ids = fileIdsOf(instances);
    result.fileIds = ids;
    Deidentifier deidentifier; // one UID map for the whole export
    deidentifier.usePatientIdPseudonyms("ANON");
    const int total = static_cast<int>(instances.size());
    for (int k = 0; k < total; ++k) {
        if (options.stop.stop_requested()) {
            throw ExportError(output.string() + ": export cancelled, nothing written");
        }
        const fs::path& source = instances[k].file;
        const fs::path target = staging.path() / ids[k];
        fs::create_directories(target.parent_path(), ec);
        if (options.anonymize) {
            try {
                deidentifier.deidentifyFile(source, target);
            } catch (const DeidentifyError& e) {
                throw ExportError(std::string("cannot export: ") + e.what());
            }
        } else if (!fs::copy_file(source, target, ec)) {
            throw ExportError(output.string() + ": cannot copy " + source.string() + " (" +
                              ec.message() + ")");
        }
        ++result.files;
        if (options.onProgress) {
            options.onProgress(k + 1, total);
        }
    }
    if (options.dicomdir) {
        writeDicomdir(staging.path(), ids);
    }
    if (result.zip) {
        StagingPath zip(siblingOf(output, ".zip"));
        zipFolder(staging.path(), zip.path());
        fs::rename(zip.path(), output, ec);
        if (!ec) {
            zip.keep();
        }
    } else {
        fs::rename(staging.path(), output, ec);
        if (!ec) {
            staging.keep();
        }
    }
    if (ec) {
        throw ExportError(output.string() + ": cannot move the export into place (" + ec.message() +
                          ")");
    }
    return result;
}

} // namespace lucent
