#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/LoadControl.h"
#include "core/io/SeriesEntry.h"

namespace lucent {

// A file that was looked at and not used, with the reason in words.
struct SkippedFile {
    std::string file;
    std::string reason;
};

// Everything loadable under a path: DICOM series (a folder searched
// recursively, a file, or a DICOMDIR), or one MetaImage, NIfTI or InVesalius file.
struct Catalog {
    std::vector<SeriesEntry> series;
    std::vector<SkippedFile> skipped;

    // By id first, then by series UID (preferring a volume over a localizer).
    const SeriesEntry* find(std::string_view idOrUid) const;
    // The entry to open when the user names none: the largest volume.
    const SeriesEntry* defaultEntry() const;
};

// Reads headers only. Throws LoadError when the path does not exist or cannot be read.
Catalog scanPath(const std::filesystem::path& path, const LoadControl& control = {});

// Decodes one entry into a volume with entry.geometry. Throws LoadError naming
// the file on bad data, LoadCancelled when control.stop is requested.
Volume loadSeries(const SeriesEntry& entry, const LoadControl& control = {});

// scanPath + loadSeries of the entry with this id or UID (or the default entry when empty).
Volume loadPath(const std::filesystem::path& path, std::string_view idOrUid = {},
                const LoadControl& control = {});

} // namespace lucent
