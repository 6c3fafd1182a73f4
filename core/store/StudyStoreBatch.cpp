// StudyStore's batches: the index writes of a retrieval in one transaction,
// and what a failed commit undoes (the files of the rows it lost).
#include "core/store/StudyStore.h"

#include <system_error>

namespace lucent {

namespace fs = std::filesystem;

StudyStore::Batch::Batch(StudyStore& store) : store_(store) {
    if (store_.batchDepth_++ == 0) {
        store_.exec("BEGIN IMMEDIATE");
    }
}

StudyStore::Batch::~Batch() {
    if (store_.batchDepth_ == 1) {
        try {
            store_.commitBatch(false);
        } catch (const StoreError&) {
            // Rows lost here (and their files, removed) are fetched again; never throw from here.
        }
    }
    --store_.batchDepth_;
}

void StudyStore::commitBatch(bool batchGoesOn) {
    try {
        exec("COMMIT");
    } catch (const StoreError& e) {
        dropUncommitted(batchGoesOn);
        throw writeError(root_ / "index.sqlite", e.what());
    }
    uncommitted_.clear();
    if (batchGoesOn) {
        exec("BEGIN IMMEDIATE");
    }
}

void StudyStore::dropUncommitted(bool batchGoesOn) {
    if (batchDepth_ == 0) {
        return;
    }
    try {
        exec("ROLLBACK");
    } catch (const StoreError&) {
        // SQLite already rolled back (it may, when the disk is full).
    }
    std::error_code ec;
    for (const fs::path& file : uncommitted_) {
        fs::remove(file, ec);
    }
    uncommitted_.clear();
    if (batchGoesOn) {
        try {
            exec("BEGIN IMMEDIATE"); // the batch's end commits it
        } catch (const StoreError&) {
            // Then the batch's end finds nothing to commit; the first error is the one to report.
        }
    }
}

} // namespace lucent
