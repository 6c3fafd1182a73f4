#pragma once

#include <filesystem>
#include <functional>
#include <stop_token>
#include <string>

#include "core/pacs/PacsNode.h"
#include "core/store/StudyStore.h"

namespace lucent {

struct RetrieveResult {
    std::string seriesUid;
    int expected = 0;      // instances the PACS lists for the series
    int received = 0;      // arrived now and stored
    int alreadyStored = 0; // in the store before, not asked for again
    int failed = 0;        // arrived but could not be stored
    bool complete = false;
    std::filesystem::path folder;
};

struct RetrieveControl {
    std::function<void(int done, int total)> onProgress; // instances handled / to fetch
    std::stop_token stop; // cancel: the association (or HTTP request) is aborted
};

// Retrieves a series by C-GET into the store, asking only for the instances the
// store lacks. Throws PacsError (network, PACS) or StoreError (disk, index);
// what arrived before a failure stays stored and the series stays incomplete.
RetrieveResult retrieveSeries(const PacsNode& node, const PacsSettings& settings,
                              const std::string& studyUid, const std::string& seriesUid,
                              StudyStore& store, const RetrieveControl& control = {});

// Retrieves a series by C-MOVE: the PACS sends the instances the store lacks
// to destinationAe, a storage SCP it knows (Lucent's StorageScp on the same
// store). Throws PacsError, e.g. when the PACS does not know the destination.
// Progress counts the PACS's sub-operations; cancel sends C-CANCEL and aborts
// the association, which stops the PACS sending.
RetrieveResult moveSeries(const PacsNode& node, const PacsSettings& settings,
                          const std::string& destinationAe, const std::string& studyUid,
                          const std::string& seriesUid, StudyStore& store,
                          const RetrieveControl& control = {});

} // namespace lucent
