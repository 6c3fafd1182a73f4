#include "core/io/Catalog.h"

#include <algorithm>
#include <cctype>
#include <optional>
#include <system_error>

#include <unistd.h>

#include "core/dicom/ImageRecord.h"
#include "core/dicom/SeriesLoader.h"
#include "core/dicom/SeriesScanner.h"
#include "core/formats/InVesaliusProject.h"
#include "core/formats/MetaImage.h"
#include "core/formats/Nifti.h"

namespace lucent {
namespace {

namespace fs = std::filesystem;

bool endsWith(std::string name, std::string_view suffix) {
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return name.size() >= suffix.size() &&
           name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::optional<SourceFormat> volumeFileFormat(const fs::path& p) {
    const std::string name = p.filename().string();
    if (endsWith(name, ".mhd") || endsWith(name, ".mha")) {
        return SourceFormat::MetaImage;
    }
    if (endsWith(name, ".nii") || endsWith(name, ".nii.gz")) {
        return SourceFormat::Nifti;
    }
    if (endsWith(name, ".inv3")) {
        return SourceFormat::InVesalius;
    }
    return std::nullopt;
}

SeriesEntry volumeFileEntry(const fs::path& p, SourceFormat format) {
    VolumeFileHeader h;
    switch (format) {
    case SourceFormat::MetaImage:
        h = readMetaImageHeader(p);
        break;
    case SourceFormat::Nifti:
        h = readNiftiHeader(p);
        break;
    case SourceFormat::InVesalius:
        h = readInVesaliusHeader(p);
        break;
    case SourceFormat::Dicom:
        break;
    }
    SeriesEntry e;
    e.id = p.string();
    e.seriesUid = p.string();
    e.file = p.string();
    e.format = format;
    e.modality = h.modality;
    e.description = h.description.empty() ? p.filename().string() : h.description;
    e.geometry = h.geometry;
    e.voxelType = h.voxelType;
    e.warnings = h.warnings;
    e.kind = h.geometry.dims.z > 1 ? SeriesKind::Volume : SeriesKind::Image;
    return e;
}

// Every regular file below a folder; folders that cannot be read are reported, not fatal.
std::vector<std::string> filesBelow(const fs::path& root, std::vector<SkippedFile>& skipped) {
    std::vector<std::string> files;
    std::error_code ec;
    fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec);
    if (ec) {
        throw LoadError(root.string() + ": cannot read folder (" + ec.message() + ")");
    }
    for (; it != fs::recursive_directory_iterator(); it.increment(ec)) {
        if (ec) {
            skipped.push_back({it->path().string(), "cannot read: " + ec.message()});
            ec.clear();
            continue;
        }
        std::error_code fileEc;
        if (it->is_directory(fileEc) && ::access(it->path().c_str(), R_OK | X_OK) != 0) {
            skipped.push_back({it->path().string(), "folder not readable (permission denied)"});
            continue;
        }
        if (it->is_regular_file(fileEc)) {
            files.push_back(it->path().string());
        }
    }
    std::sort(files.begin(), files.end());
    return files;
}

} // namespace

const char* seriesKindName(SeriesKind kind) {
    switch (kind) {
    case SeriesKind::Volume:
        return "volume";
    case SeriesKind::Localizer:
        return "localizer";
    case SeriesKind::Image:
        return "image";
    case SeriesKind::Stack:
        return "stack";
    }
    return "?";
}

const SeriesEntry* Catalog::find(std::string_view idOrUid) const {
    for (const SeriesEntry& e : series) {
        if (e.id == idOrUid) {
            return &e;
        }
    }
    const SeriesEntry* best = nullptr;
    for (const SeriesEntry& e : series) {
        if (e.seriesUid == idOrUid && (best == nullptr || (best->kind != SeriesKind::Volume &&
                                                           e.kind == SeriesKind::Volume))) {
            best = &e;
        }
    }
    return best;
}

const SeriesEntry* Catalog::defaultEntry() const {
    const SeriesEntry* best = nullptr;
    auto rank = [](const SeriesEntry& e) {
        return std::pair(e.kind == SeriesKind::Volume  ? 2
                         : e.kind == SeriesKind::Image ? 1
                                                       : 0,
                         e.geometry.voxelCount());
    };
    for (const SeriesEntry& e : series) {
        if (best == nullptr || rank(e) > rank(*best)) {
            best = &e;
        }
    }
    return best;
}

Catalog scanPath(const fs::path& path, const LoadControl& control) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (ec || !fs::exists(status)) {
        throw LoadError(path.string() + ": no such file or folder");
    }
    Catalog catalog;
    if (fs::is_directory(status)) {
        if (::access(path.c_str(), R_OK | X_OK) != 0) {
            throw LoadError(path.string() + ": folder not readable (permission denied)");
        }
        std::vector<std::string> dicomFiles;
        for (std::string& f : filesBelow(path, catalog.skipped)) {
            if (const auto format = volumeFileFormat(f)) {
                try {
                    catalog.series.push_back(volumeFileEntry(f, *format));
                } catch (const std::exception& e) {
                    catalog.skipped.push_back({f, e.what()});
                }
            } else if (!endsWith(f, ".raw") && !endsWith(f, ".img")) {
                dicomFiles.push_back(std::move(f));
            }
        }
        scanDicomFiles(dicomFiles, catalog, control);
        return catalog;
    }
    if (::access(path.c_str(), R_OK) != 0) {
        throw LoadError(path.string() + ": file not readable (permission denied)");
    }
    if (const auto format = volumeFileFormat(path)) {
        catalog.series.push_back(volumeFileEntry(path, *format));
        return catalog;
    }
    if (isDicomdir(path.string())) {
        scanDicomFiles(dicomdirReferences(path.string()), catalog, control);
    } else {
        scanDicomFiles({path.string()}, catalog, control);
    }
    return catalog;
}

Volume loadSeries(const SeriesEntry& entry, const LoadControl& control) {
    if (entry.kind == SeriesKind::Stack) {
        throw LoadError("series " + entry.id + " (" + entry.pixels.photometric +
                        ") is a 2D image stack, not a volume: open it with loadStack");
    }
    Volume v;
    switch (entry.format) {
    case SourceFormat::Dicom:
        return loadDicomSeries(entry, control);
    case SourceFormat::MetaImage:
        v = readMetaImage(entry.file);
        break;
    case SourceFormat::Nifti:
        v = readNifti(entry.file);
        break;
    case SourceFormat::InVesalius:
        v = readInVesalius(entry.file);
        break;
    }
    if (v.modality.empty()) {
        v.modality = entry.modality;
    }
    if (v.description.empty()) {
        v.description = entry.description;
    }
    v.seriesUid = entry.seriesUid;
    v.warnings = entry.warnings;
    return v;
}

Volume loadPath(const fs::path& path, std::string_view idOrUid, const LoadControl& control) {
    const Catalog catalog = scanPath(path, control);
    const SeriesEntry* entry = idOrUid.empty() ? catalog.defaultEntry() : catalog.find(idOrUid);
    if (entry == nullptr) {
        if (!idOrUid.empty()) {
            throw LoadError(path.string() + ": no series with id or UID " + std::string(idOrUid));
        }
        std::string why = path.string() + ": nothing loadable";
        if (!catalog.skipped.empty()) {
            why += " (" + catalog.skipped.front().file + ": " + catalog.skipped.front().reason +
                   (catalog.skipped.size() > 1
                        ? "; and " + std::to_string(catalog.skipped.size() - 1) + " more"
                        : "") +
                   ")";
        }
        throw LoadError(why);
    }
    return loadSeries(*entry, control);
}

} // namespace lucent
