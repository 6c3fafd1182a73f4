#pragma once
// Real files copied into a study store, as a retrieval would store them.

#include <QTest>

#include <filesystem>
#include <string>

#include "core/exchange/InstanceFiles.h"
#include "core/store/StudyStore.h"

namespace lucent::test {

inline bool storeCopy(StudyStore& store, const std::filesystem::path& file,
                      const std::string& modality) {
    const InstanceHeader h = readInstanceHeader(file);
    InstanceRecord r;
    r.series.seriesUid = h.seriesUid;
    r.series.studyUid = h.studyUid;
    r.series.modality = modality;
    r.series.patientName = "Phantom";
    r.sopInstanceUid = h.sopInstanceUid;
    const std::filesystem::path temp = store.temporaryFile();
    std::filesystem::copy_file(file, temp);
    return store.add(temp, r);
}

} // namespace lucent::test
