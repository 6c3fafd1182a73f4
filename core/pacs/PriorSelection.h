#pragma once
// Which of a patient's other studies is "prior 1, prior 2, ...": the studies found in the
// local store and on each PACS node are merged into one list by Study Instance UID, and
// those older than the current study that are comparable to it (same modality, same body
// part where both say one) are numbered newest first. Free of Qt and of the network, so
// the rule is tested on its own and used by PriorsForStudy.

#include <string>
#include <vector>

#include "core/pacs/DimseQuery.h"
#include "core/store/StudyStore.h"

namespace lucent {

// The study being read: what its priors are compared with.
struct CurrentStudy {
    std::string patientId;
    std::string studyUid;
    std::string modality;
    std::string bodyPart;
    std::string studyDate; // YYYYMMDD
    std::string studyTime; // HHMMSS(.frac), may be empty
};

// A series of a patient's study, as the store or a PACS lists it.
struct PatientSeries {
    std::string seriesUid;
    std::string modality;
    std::string bodyPart;
    std::string description;
    int instances = 0;
    bool completeInStore = false;
};

// One of the patient's studies, wherever it is.
struct PatientStudy {
    std::string studyUid;
    std::string studyDate;
    std::string studyTime;
    std::string description;
    std::vector<PatientSeries> series;
    std::vector<int> nodes;  // indices of the PACS nodes that have it
    std::string storeFolder; // files/<study> in the store; empty when none of it is there
    bool comparable = false; // with the current study
    int order = -1;          // 0: the current study; 1, 2, ...: comparable priors; -1: other

    std::vector<std::string> modalities() const;
    std::vector<std::string> bodyParts() const;
    // Every series the store or a node lists is complete in the store.
    bool completeInStore() const;
};

// Body parts of the same region (CHEST and THORAX, HEAD and BRAIN, ...): compared
// by the upper-cased first name of the group they belong to.
std::string bodyRegion(const std::string& bodyPart);

// True when `study` has a series of the current modality whose body part is the
// current one's region, or either does not say.
bool isComparable(const PatientStudy& study, const CurrentStudy& current);

// The patient's studies in the store (series of other patients ignored).
std::vector<PatientStudy> studiesInStore(const std::vector<StoredSeries>& stored,
                                         const std::string& patientId);
// Studies a PACS node listed (study-level matches with their series-level matches).
void mergeNodeStudies(std::vector<PatientStudy>& studies, int node, const QueryMatch& study,
                      const std::vector<QueryMatch>& series);

// Marks comparability and numbers the priors: studies before the current one (by date,
// then time) that are comparable, newest first, get 1, 2, ... Sorts newest first.
void orderPriors(std::vector<PatientStudy>& studies, const CurrentStudy& current);

// Human-readable "YYYY-MM-DD, CT CHEST, 3 series" for lists and messages.
std::string describeStudy(const PatientStudy& study);

} // namespace lucent
