#include "core/segdicom/SegmentationArchive.h"

#include <algorithm>

namespace lucent {

namespace fs = std::filesystem;

SegmentationArchive::SegmentationArchive(StudyStore& store, std::string softwareVersion)
    : store_(store), softwareVersion_(std::move(softwareVersion)) {}

const ReferencedSeries& SegmentationArchive::referencedSeries(const std::string& seriesUid) {
    const auto cached = series_.find(seriesUid);
    if (cached != series_.end()) {
        return cached->second;
    }
    std::vector<fs::path> files;
    for (const auto& [sop, file] : store_.instanceFiles(seriesUid)) {
        files.push_back(file);
    }
    if (files.empty()) {
        throw SegmentationDicomError(store_.root().string() + ": series " + seriesUid +
                                     " has no images in the study store");
    }
    return series_[seriesUid] = readReferencedSeries(files);
}

std::vector<SegmentationArchive::Stored> SegmentationArchive::find(const std::string& seriesUid) {
    const std::string study = store_.studyOf(seriesUid);
    const std::set<std::string> instances = store_.instancesOf(seriesUid);
    std::vector<Stored> out;
    for (const StoredSeries& s : store_.listSeries()) {
        if (s.info.studyUid != study || s.info.modality != "SEG") {
            continue;
        }
        for (const auto& [sop, file] : store_.instanceFiles(s.info.seriesUid)) {
            try {
                SegmentationDicomHeader h = readSegmentationDicomHeader(file);
                const auto& series = h.referencedSeries;
                const bool refers =
                    std::find(series.begin(), series.end(), seriesUid) != series.end() ||
                    std::any_of(h.referencedInstances.begin(), h.referencedInstances.end(),
                                [&](const std::string& uid) { return instances.count(uid) > 0; });
                if (refers) {
                    out.push_back({file, std::move(h)});
                }
            } catch (const SegmentationDicomError&) {
                // not a SEG after all (a series' modality is what its sender said): passed over
            }
        }
    }
    std::stable_sort(out.begin(), out.end(), [](const Stored& a, const Stored& b) {
        return a.header.writtenByLucent && !b.header.writtenByLucent;
    });
    return out;
}

std::string SegmentationArchive::save(const std::string& seriesUid,
                                      const Segmentation& segmentation) {
    std::vector<std::string> previous;
    std::string segSeries;
    for (const Stored& s : find(seriesUid)) {
        if (s.header.writtenByLucent) {
            previous.push_back(s.header.sopInstanceUid);
            segSeries = s.header.seriesUid;
        }
    }
    if (segmentation.segments().empty()) {
        for (const std::string& sop : previous) {
            store_.remove(sop);
        }
        return {};
    }
    const ReferencedSeries& series = referencedSeries(seriesUid);
    InstanceRecord record = store_.recordBeside(seriesUid);
    SegmentationIdentity identity;
    identity.seriesUid = segSeries;
    identity.softwareVersion = softwareVersion_;
    const fs::path temp = store_.temporaryFile();
    const WrittenSegmentation written =
        writeSegmentationDicom(temp, segmentation, series, identity);
    record.series.seriesUid = written.seriesUid;
    record.series.modality = "SEG";
    record.series.description = identity.seriesDescription;
    record.seriesNumber = identity.seriesNumber;
    record.sopInstanceUid = written.sopInstanceUid;
    store_.replace(previous, temp, record);
    return written.sopInstanceUid;
}

SegmentationArchive::LoadResult SegmentationArchive::load(const std::string& seriesUid,
                                                          const VolumeGeometry& grid) {
    LoadResult result;
    const std::vector<Stored> stored = find(seriesUid);
    if (stored.empty()) {
        return result;
    }
    const ReferencedSeries& series = referencedSeries(seriesUid);
    for (const Stored& s : stored) {
        try {
            result.loaded.push_back({s.file, readSegmentationDicom(s.file, series, grid)});
        } catch (const SegmentationDicomError& e) {
            result.errors.push_back(e.what());
        }
    }
    return result;
}

} // namespace lucent
