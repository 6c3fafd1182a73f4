#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/volume/SeriesInfo.h"

namespace lucent {

class StoreError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// What the store keeps about one instance besides its file.
struct InstanceRecord {
    SeriesInfo series;
    int seriesNumber = 0;
    std::string sopInstanceUid;
    // Study and patient facts for the index (empty when unknown).
    std::string studyDescription;
    std::string accessionNumber;
    std::string patientBirthDate;
};

// One series of the index, for the study browser: patient, study, series and
// how complete it is.
struct StoredSeries {
    SeriesInfo info;
    std::string studyDescription;
    std::string accessionNumber;
    std::string patientBirthDate;
    int seriesNumber = 0;
    int expected = 0; // instances the PACS listed; 0 when unknown (e.g. pushed to Lucent)
    int stored = 0;
    bool complete = false; // expected known and all stored
    std::filesystem::path folder;
};

// The local study store: DICOM files under a folder
// (files/<study>/<series>/<instance>.dcm) indexed in SQLite (index.sqlite).
// A file enters the store only whole: it is written elsewhere in the store's
// tmp/ folder and renamed into place, then indexed. No instance is stored
// twice. Each series remembers how many instances the PACS said it has, so an
// interrupted retrieval shows as incomplete and a new one fetches only the rest.
// A file in files/ is always indexed: when an index write fails (a full disk),
// the files whose rows it lost are removed again, to be fetched another time.
class StudyStore {
public:
    // Opens or creates the store; removes leftovers of interrupted writes (of
    // processes no longer running). Several objects, threads and processes may
    // use one store at once. Throws StoreError.
    explicit StudyStore(const std::filesystem::path& root);
    ~StudyStore();
    StudyStore(const StudyStore&) = delete;
    StudyStore& operator=(const StudyStore&) = delete;

    const std::filesystem::path& root() const { return root_; }
    // A new, unused file name in tmp/ for writing an incoming instance.
    std::filesystem::path temporaryFile();

    // Free space kept for the index: an instance is refused rather than
    // written when it would leave less than this on the store's file system,
    // so that the index can always record (or roll back) what is stored.
    static constexpr std::uintmax_t kSpaceReserveBytes = 256 * 1024;
    // Throws StoreError naming the store and "no space" when its file system
    // cannot take `bytes` more and still keep kSpaceReserveBytes free.
    void requireSpace(std::uintmax_t bytes) const;
    // The error for a failed write of `file` (a temporary file of this store):
    // "no space" naming the store when its file system is full, else `cause`.
    StoreError writeError(const std::filesystem::path& file, const std::string& cause) const;

    bool contains(const std::string& sopInstanceUid) const;
    std::set<std::string> instancesOf(const std::string& seriesUid) const;
    // Moves the complete file into place and indexes it. Returns false (and
    // removes the file) when the instance is already stored.
    bool add(const std::filesystem::path& completeFile, const InstanceRecord& record);
    // Removes an instance's file and row (no-op when absent), and the series' row
    // with its last instance when no PACS listed the series (expected() is 0).
    void remove(const std::string& sopInstanceUid);
    // Stores `completeFile` as add() does and, in the same index transaction, drops
    // the rows of `replaced` (instances of any series); their files are removed only
    // after the commit, so the index never names a missing or half-written file and
    // readers see either the old instances or the new one. Throws StoreError.
    void replace(const std::vector<std::string>& replaced,
                 const std::filesystem::path& completeFile, const InstanceRecord& record);

    // The files of a series' instances (absolute paths), by SOP Instance UID.
    std::vector<std::pair<std::string, std::filesystem::path>>
    instanceFiles(const std::string& seriesUid) const;
    // The study of an indexed series, or "" when the index does not know it.
    std::string studyOf(const std::string& seriesUid) const;

    void setExpected(const SeriesInfo& series, int seriesNumber, int instances);
    // The same with the study and patient facts of `series` (its SOP UID is unused).
    void setExpected(const InstanceRecord& series, int instances);
    int expected(const std::string& seriesUid) const;
    bool isComplete(const std::string& seriesUid) const;
    std::filesystem::path seriesFolder(const std::string& studyUid,
                                       const std::string& seriesUid) const;

    // Every series of the index (patients, studies, series with their
    // completeness), ordered by patient name, study date, study, series number.
    std::vector<StoredSeries> listSeries() const;
    // A record for an object derived from the series (an SR, a SEG) to store in its study:
    // the series' patient, study and series facts, to be given the object's own series,
    // modality and SOP instance. Empty facts when the series is not in the index.
    InstanceRecord recordBeside(const std::string& seriesUid) const;

    // The offset "link here" set between two series in different Frames of Reference
    // (linked viewports): a point in b is the point in a plus the offset, LPS mm. One
    // per pair; asked in the other order, the offset comes back negated.
    void setSeriesOffset(const std::string& seriesA, const std::string& seriesB,
                         const glm::dvec3& offset);
    std::optional<glm::dvec3> seriesOffset(const std::string& seriesA,
                                           const std::string& seriesB) const;
    // A registration's transform between two series (a point of a, LPS mm, to the same
    // anatomy in b). One per pair; asked in the other order, the inverse comes back.
    void setSeriesTransform(const std::string& seriesA, const std::string& seriesB,
                            const glm::dmat4& aToB);
    std::optional<glm::dmat4> seriesTransform(const std::string& seriesA,
                                              const std::string& seriesB) const;

    // Groups the index writes of a retrieval into one transaction (one commit
    // instead of one per instance). Commits when destroyed, also on an
    // exception: every row it holds describes a file already in place. Nests.
    class Batch {
    public:
        explicit Batch(StudyStore& store);
        ~Batch();
        Batch(const Batch&) = delete;
        Batch& operator=(const Batch&) = delete;

    private:
        StudyStore& store_;
    };

private:
    void exec(const std::string& sql) const;
    void upsertStudy(const InstanceRecord& r);
    void indexInstance(const std::filesystem::path& target, const InstanceRecord& r);
    // Commits the batch's rows (and begins anew when it goes on); on failure
    // rolls back and removes their files.
    void commitBatch(bool batchGoesOn);
    // After a failed index write: the transaction's rows are gone (SQLite may
    // roll back on its own when the disk is full), so are their files.
    void dropUncommitted(bool batchGoesOn);

    int batchDepth_ = 0;
    std::uint64_t batchAdds_ = 0;
    std::vector<std::filesystem::path> uncommitted_; // files of the open batch's rows

    std::filesystem::path root_;
    std::string connection_;
    std::string tempPrefix_; // unique to this object: several may share a store
    std::uint64_t counter_ = 0;
};

} // namespace lucent
