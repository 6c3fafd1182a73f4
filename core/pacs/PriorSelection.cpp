#include "core/pacs/PriorSelection.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <set>
#include <string_view>

#include "core/volume/SeriesInfo.h"

namespace lucent {

namespace {

std::string upper(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    // BodyPartExamined is a code string: trailing pad spaces are not part of it.
    while (!text.empty() && text.back() == ' ') {
        text.pop_back();
    }
    return text;
}

// Names scanners write for one region (DICOM PS3.16 Annex L's codes and common
// free text), the first being the group's name.
constexpr std::array<std::array<std::string_view, 5>, 5> kRegions{{
    {"CHEST", "THORAX", "LUNG", "CHEST_TO_PELVIS", ""},
    {"HEAD", "BRAIN", "SKULL", "HEADNECK", ""},
    {"ABDOMEN", "ABD", "ABDOMENPELVIS", "LIVER", ""},
    {"PELVIS", "HIP", "", "", ""},
    {"SPINE", "CSPINE", "TSPINE", "LSPINE", ""},
}};

PatientStudy& studyOf(std::vector<PatientStudy>& studies, const std::string& uid) {
    const auto found = std::find_if(studies.begin(), studies.end(),
                                    [&](const PatientStudy& s) { return s.studyUid == uid; });
    if (found != studies.end()) {
        return *found;
    }
    studies.push_back({});
    studies.back().studyUid = uid;
    return studies.back();
}

PatientSeries& seriesOf(PatientStudy& study, const std::string& uid) {
    const auto found = std::find_if(study.series.begin(), study.series.end(),
                                    [&](const PatientSeries& s) { return s.seriesUid == uid; });
    if (found != study.series.end()) {
        return *found;
    }
    study.series.push_back({});
    study.series.back().seriesUid = uid;
    return study.series.back();
}

void fill(std::string& field, const std::string& value) {
    if (field.empty()) {
        field = value;
    }
}

// Date then time, as strings of digits compare: "" sorts first.
bool before(const PatientStudy& a, const std::string& date, const std::string& time) {
    return a.studyDate != date ? a.studyDate < date : a.studyTime.substr(0, 6) < time.substr(0, 6);
}

} // namespace

std::string bodyRegion(const std::string& bodyPart) {
    const std::string part = upper(bodyPart);
    for (const auto& region : kRegions) {
        if (std::find(region.begin(), region.end(), part) != region.end() && !part.empty()) {
            return std::string(region.front());
        }
    }
    return part;
}

std::vector<std::string> PatientStudy::modalities() const {
    std::set<std::string> all;
    for (const PatientSeries& s : series) {
        if (!s.modality.empty()) {
            all.insert(s.modality);
        }
    }
    return {all.begin(), all.end()};
}

std::vector<std::string> PatientStudy::bodyParts() const {
    std::set<std::string> all;
    for (const PatientSeries& s : series) {
        if (!s.bodyPart.empty()) {
            all.insert(upper(s.bodyPart));
        }
    }
    return {all.begin(), all.end()};
}

bool PatientStudy::completeInStore() const {
    return !storeFolder.empty() && !series.empty() &&
           std::all_of(series.begin(), series.end(),
                       [](const PatientSeries& s) { return s.completeInStore; });
}

bool isComparable(const PatientStudy& study, const CurrentStudy& current) {
    const std::string region = bodyRegion(current.bodyPart);
    return std::any_of(study.series.begin(), study.series.end(), [&](const PatientSeries& s) {
        return s.modality == current.modality &&
               (region.empty() || s.bodyPart.empty() || bodyRegion(s.bodyPart) == region);
    });
}

std::vector<PatientStudy> studiesInStore(const std::vector<StoredSeries>& stored,
                                         const std::string& patientId) {
    std::vector<PatientStudy> studies;
    for (const StoredSeries& s : stored) {
        if (s.info.patientId != patientId || patientId.empty()) {
            continue;
        }
        PatientStudy& study = studyOf(studies, s.info.studyUid);
        fill(study.studyDate, s.info.studyDate);
        fill(study.description, s.studyDescription);
        study.storeFolder = s.folder.parent_path().string();
        PatientSeries& series = seriesOf(study, s.info.seriesUid);
        series.modality = s.info.modality;
        series.description = s.info.description;
        series.instances = s.stored;
        // Pushed to Lucent (no PACS listed it): complete as far as anyone knows.
        series.completeInStore = s.complete || (s.expected == 0 && s.stored > 0);
    }
    return studies;
}

void mergeNodeStudies(std::vector<PatientStudy>& studies, int node, const QueryMatch& match,
                      const std::vector<QueryMatch>& series) {
    PatientStudy& study = studyOf(studies, match.studyUid);
    fill(study.studyDate, match.studyDate);
    fill(study.studyTime, match.studyTime);
    fill(study.description, match.studyDescription);
    if (std::find(study.nodes.begin(), study.nodes.end(), node) == study.nodes.end()) {
        study.nodes.push_back(node);
    }
    for (const QueryMatch& m : series) {
        PatientSeries& s = seriesOf(study, m.seriesUid);
        fill(s.modality, m.modality);
        fill(s.bodyPart, m.bodyPart);
        fill(s.description, m.seriesDescription);
        s.instances = std::max(s.instances, m.instances);
    }
}

void orderPriors(std::vector<PatientStudy>& studies, const CurrentStudy& current) {
    std::stable_sort(studies.begin(), studies.end(),
                     [](const PatientStudy& a, const PatientStudy& b) {
                         return before(b, a.studyDate, a.studyTime);
                     });
    int next = 1;
    for (PatientStudy& s : studies) {
        s.comparable = isComparable(s, current);
        s.order = -1;
        if (s.studyUid == current.studyUid) {
            s.order = 0;
        } else if (s.comparable && before(s, current.studyDate, current.studyTime)) {
            s.order = next++;
        }
    }
}

std::string describeStudy(const PatientStudy& study) {
    std::string text = formatStudyDate(study.studyDate);
    std::string kinds;
    for (const std::string& m : study.modalities()) {
        kinds += (kinds.empty() ? "" : "/") + m;
    }
    for (const std::string& b : study.bodyParts()) {
        kinds += " " + b;
    }
    if (!kinds.empty()) {
        text += ", " + kinds;
    }
    if (!study.description.empty()) {
        text += ", " + study.description;
    }
    return text + ", " + std::to_string(study.series.size()) + " series";
}

} // namespace lucent
