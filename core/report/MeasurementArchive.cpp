#include "core/report/MeasurementArchive.h"

#include <algorithm>

#include "core/report/MeasurementReport.h"

namespace lucent {

namespace fs = std::filesystem;

MeasurementArchive::MeasurementArchive(StudyStore& store, std::string softwareVersion)
    : store_(store), softwareVersion_(std::move(softwareVersion)) {}

const ReferencedSeries& MeasurementArchive::referencedSeries(const std::string& seriesUid) {
    const auto cached = series_.find(seriesUid);
    if (cached != series_.end()) {
        return cached->second;
    }
    std::vector<fs::path> files;
    for (const auto& [sop, file] : store_.instanceFiles(seriesUid)) {
        if (!isStructuredReport(file)) {
            files.push_back(file);
        }
    }
    if (files.empty()) {
        throw ReportError(store_.root().string() + ": series " + seriesUid +
                          " has no images in the study store");
    }
    return series_[seriesUid] = readReferencedSeries(files);
}

std::vector<MeasurementArchive::StoredReport>
MeasurementArchive::reportsOf(const std::string& seriesUid, Loaded* read) {
    const std::string study = store_.studyOf(seriesUid);
    std::vector<StoredReport> out;
    for (const StoredSeries& s : store_.listSeries()) {
        if (s.info.studyUid != study || s.info.modality != "SR") {
            continue;
        }
        for (const auto& [sop, file] : store_.instanceFiles(s.info.seriesUid)) {
            try {
                const ReadReport report =
                    readMeasurementReport(file, read ? &referencedSeries(seriesUid) : nullptr);
                const auto& refs = report.referencedSeries;
                if (std::find(refs.begin(), refs.end(), seriesUid) == refs.end()) {
                    continue;
                }
                out.push_back({sop, s.info.seriesUid, file, report.writtenByLucent});
                if (read) {
                    read->reports.push_back(file);
                    read->measurements.insert(read->measurements.end(), report.measurements.begin(),
                                              report.measurements.end());
                    read->notShown.insert(read->notShown.end(), report.notShown.begin(),
                                          report.notShown.end());
                }
            } catch (const ReportError& e) {
                if (read) {
                    read->notShown.push_back(e.what()); // another kind of SR: listed, not shown
                }
            }
        }
    }
    return out;
}

std::string MeasurementArchive::save(const std::string& seriesUid,
                                     const std::vector<Measurement>& measurements) {
    std::vector<std::string> previous;
    std::string reportSeries;
    for (const StoredReport& r : reportsOf(seriesUid, nullptr)) {
        if (r.writtenByLucent) {
            previous.push_back(r.sopInstanceUid);
            reportSeries = r.seriesUid;
        }
    }
    std::vector<Measurement> editable;
    std::copy_if(measurements.begin(), measurements.end(), std::back_inserter(editable),
                 [](const Measurement& m) { return !m.readOnly && m.complete(); });
    if (editable.empty()) {
        for (const std::string& sop : previous) {
            store_.remove(sop);
        }
        return {};
    }
    const ReferencedSeries& series = referencedSeries(seriesUid);
    InstanceRecord record = store_.recordBeside(seriesUid);
    ReportIdentity identity;
    identity.seriesUid = reportSeries;
    identity.softwareVersion = softwareVersion_;
    const fs::path temp = store_.temporaryFile();
    const WrittenReport written = writeMeasurementReport(temp, series, editable, identity);
    record.series.seriesUid = written.seriesUid;
    record.series.modality = "SR";
    record.series.description = "Lucent measurements";
    record.seriesNumber = identity.seriesNumber;
    record.sopInstanceUid = written.sopInstanceUid;
    store_.replace(previous, temp, record);
    return written.sopInstanceUid;
}

MeasurementArchive::Loaded MeasurementArchive::load(const std::string& seriesUid) {
    Loaded loaded;
    reportsOf(seriesUid, &loaded);
    return loaded;
}

} // namespace lucent
