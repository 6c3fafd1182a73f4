#pragma once
// The measurements of a series kept in the local study store as Lucent's SR
// (core/report/MeasurementReport.h): one SR instance per measured series, in its
// own series of the same study. The UI calls save() on every change of a
// series' MeasurementDocument (revision()) and load() when it opens the series.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/measure/Measurement.h"
#include "core/report/ReferencedSeries.h"
#include "core/store/StudyStore.h"

namespace lucent {

class MeasurementArchive {
public:
    explicit MeasurementArchive(StudyStore& store, std::string softwareVersion = "Lucent");

    // Saves the editable, complete measurements of a stored series as a new SR that
    // replaces Lucent's previous SR of that series in one step (the index never
    // names a half-written file); with none left, removes that SR. Returns the new
    // SR's SOP Instance UID, or "" when removed. Throws ReportError or StoreError
    // naming the series or file; what was stored before stays then.
    std::string save(const std::string& seriesUid, const std::vector<Measurement>& measurements);

    struct Loaded {
        std::vector<Measurement> measurements;      // Lucent's editable, others read-only
        std::vector<std::string> notShown;          // items of other SRs Lucent cannot show
        std::vector<std::filesystem::path> reports; // the SR files read
    };
    // The measurements of a stored series from every SR of its study that refers to it.
    Loaded load(const std::string& seriesUid);

private:
    struct StoredReport {
        std::string sopInstanceUid;
        std::string seriesUid;
        std::filesystem::path file;
        bool writtenByLucent = false;
    };
    const ReferencedSeries& referencedSeries(const std::string& seriesUid);
    // The SRs of the series' study that refer to it (read fully into `read` when given).
    std::vector<StoredReport> reportsOf(const std::string& seriesUid, Loaded* read);

    StudyStore& store_;
    std::string softwareVersion_;
    std::map<std::string, ReferencedSeries> series_; // headers read once per series
};

} // namespace lucent
