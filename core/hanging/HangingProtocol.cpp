// Hanging-protocol matching: study order, series scores, slot assignment, ranking.
#include "core/hanging/HangingProtocol.h"
#include "core/hanging/HangingProtocolNames_p.h"

#include <algorithm>
#include <map>
#include <regex>
#include <set>
#include <stdexcept>
#include <tuple>

namespace lucent {

namespace {

bool anyModality(const std::vector<std::string>& wanted, const std::string& modality) {
    return std::any_of(wanted.begin(), wanted.end(),
                       [&](const std::string& m) { return equalNoCase(m, modality); });
}

// Regexes of a protocol, compiled once per ranking.
class RegexCache {
public:
    bool search(const std::string& pattern, const std::string& text, const std::string& where) {
        auto it = compiled_.find(pattern);
        if (it == compiled_.end()) {
            try {
                it = compiled_
                         .emplace(pattern,
                                  std::regex(pattern, std::regex::ECMAScript | std::regex::icase))
                         .first;
            } catch (const std::regex_error& e) {
                throw std::invalid_argument(where + ": bad regular expression '" + pattern +
                                            "': " + e.what());
            }
        }
        return std::regex_search(text, it->second);
    }

private:
    std::map<std::string, std::regex> compiled_;
};

// Adds a criterion's weight when it matches; false when it must match and does not.
struct Tally {
    const CriterionScoring& scoring;
    double score = 0;
    std::string failed; // the first criterion that had to match and did not

    void add(Criterion c, bool matched) {
        if (matched) {
            score += scoring.weightOf(c);
        } else if (scoring.mustMatchOf(c) && failed.empty()) {
            failed = criterionName(c);
        }
    }
};

std::optional<double> scoreWith(const SeriesRule& rule, const HangingSeries& s, RegexCache& regexes,
                                const std::string& where) {
    if (s.studyOrder < 0 || (rule.studyOrder != kAnyStudy && s.studyOrder != rule.studyOrder)) {
        return std::nullopt;
    }
    Tally t{rule.scoring, 0.0, {}};
    if (!rule.modalities.empty()) {
        t.add(Criterion::Modality, anyModality(rule.modalities, s.modality));
    }
    if (!rule.bodyPart.empty()) {
        t.add(Criterion::BodyPart, regexes.search(rule.bodyPart, s.bodyPart, where + ": bodyPart"));
    }
    if (!rule.description.empty()) {
        t.add(Criterion::Description,
              regexes.search(rule.description, s.description, where + ": description"));
    }
    if (rule.minSliceThickness || rule.maxSliceThickness) {
        const bool known = s.sliceThickness > 0;
        t.add(Criterion::SliceThickness,
              known && s.sliceThickness >= rule.minSliceThickness.value_or(0) &&
                  s.sliceThickness <= rule.maxSliceThickness.value_or(1e300));
    }
    if (!rule.orientations.empty()) {
        t.add(Criterion::Orientation, std::find(rule.orientations.begin(), rule.orientations.end(),
                                                s.orientation) != rule.orientations.end());
    }
    if (rule.minInstances || rule.maxInstances) {
        t.add(Criterion::Instances, s.instances >= rule.minInstances.value_or(0) &&
                                        s.instances <= rule.maxInstances.value_or(1 << 30));
    }
    if (!rule.kinds.empty()) {
        t.add(Criterion::Kind,
              std::find(rule.kinds.begin(), rule.kinds.end(), s.kind) != rule.kinds.end());
    }
    if (!t.failed.empty()) {
        return std::nullopt;
    }
    return t.score;
}

// The study rule on the current study (studyOrder 0); the reason when it fails.
std::optional<double> scoreStudy(const HangingProtocol& p, const std::vector<HangingSeries>& series,
                                 RegexCache& regexes, std::string& reason) {
    const StudyRule& rule = p.study;
    std::vector<const HangingSeries*> current;
    for (const HangingSeries& s : series) {
        if (s.studyOrder == 0) {
            current.push_back(&s);
        }
    }
    const std::string where = p.name + ": study";
    Tally t{rule.scoring, 0.0, {}};
    const auto any = [&](auto predicate) {
        return std::any_of(current.begin(), current.end(), predicate);
    };
    if (!rule.modalities.empty()) {
        t.add(Criterion::Modality, any([&](const HangingSeries* s) {
                  return anyModality(rule.modalities, s->modality);
              }));
    }
    if (!rule.bodyPart.empty()) {
        t.add(Criterion::BodyPart, any([&](const HangingSeries* s) {
                  return regexes.search(rule.bodyPart, s->bodyPart, where + ": bodyPart") ||
                         regexes.search(rule.bodyPart, s->studyDescription, where + ": bodyPart");
              }));
    }
    if (!rule.description.empty()) {
        t.add(Criterion::Description, any([&](const HangingSeries* s) {
                  return regexes.search(rule.description, s->studyDescription,
                                        where + ": description");
              }));
    }
    if (!t.failed.empty()) {
        reason = "the current study does not match the study rule's " + t.failed;
        return std::nullopt;
    }
    return t.score;
}

// Better candidate first: higher score, more images, lower series number, then UID and id.
bool betterCandidate(double scoreA, const HangingSeries& a, double scoreB, const HangingSeries& b) {
    return std::make_tuple(-scoreA, -a.instances, a.seriesNumber, a.seriesUid, a.id) <
           std::make_tuple(-scoreB, -b.instances, b.seriesNumber, b.seriesUid, b.id);
}

bool studyPresent(const std::vector<HangingSeries>& series, int order) {
    return std::any_of(series.begin(), series.end(),
                       [order](const HangingSeries& s) { return s.studyOrder == order; });
}

// Fills result.slotAssignments, score, applicable, reason and missingStudyOrders.
void assignSlots(const HangingProtocol& p, const std::vector<HangingSeries>& series,
                 const RankOptions& options, RegexCache& regexes, HangingResult& result) {
    std::string reason;
    const std::optional<double> studyScore = scoreStudy(p, series, regexes, reason);
    result.applicable = studyScore.has_value();
    result.reason = reason;
    result.score = p.priority + studyScore.value_or(0);
    std::set<int> taken;
    std::set<int> missing;
    for (const SeriesRule& rule : p.seriesSlots) {
        SlotAssignment slot;
        slot.slot = rule.name;
        const std::string where = p.name + ": series '" + rule.name + "'";
        for (int i = 0; i < static_cast<int>(series.size()); ++i) {
            if (taken.count(i)) {
                continue;
            }
            const std::optional<double> score = scoreWith(rule, series[i], regexes, where);
            if (score && (slot.seriesIndex < 0 || betterCandidate(*score, series[i], slot.score,
                                                                  series[slot.seriesIndex]))) {
                slot.seriesIndex = i;
                slot.score = *score;
            }
        }
        const bool absentStudy = rule.studyOrder > 0 && !studyPresent(series, rule.studyOrder);
        if (absentStudy) {
            missing.insert(rule.studyOrder);
        }
        if (slot.seriesIndex >= 0) {
            taken.insert(slot.seriesIndex);
            result.score += slot.score;
        } else if (rule.required && (!absentStudy || options.allPriorsPresent) &&
                   result.applicable) {
            result.applicable = false;
            result.reason =
                "no series for the required slot '" + rule.name + "'" +
                (absentStudy ? " (prior " + std::to_string(rule.studyOrder) + " is not there)"
                             : "");
        }
        result.slotAssignments.push_back(slot);
    }
    // Fallbacks take the series of another slot (after all slots chose their own).
    for (std::size_t n = 0; n < p.seriesSlots.size(); ++n) {
        const SeriesRule& rule = p.seriesSlots[n];
        if (result.slotAssignments[n].seriesIndex >= 0 || rule.fallback.empty()) {
            continue;
        }
        for (const SlotAssignment& other : result.slotAssignments) {
            if (other.slot == rule.fallback && other.seriesIndex >= 0 && !other.fromFallback) {
                result.slotAssignments[n].seriesIndex = other.seriesIndex;
                result.slotAssignments[n].fromFallback = true;
            }
        }
    }
    result.missingStudyOrders.assign(missing.begin(), missing.end());
}

void placeViewports(const HangingProtocol& p, const std::vector<HangingSeries>& series,
                    HangingResult& result) {
    result.viewports.clear();
    if (p.viewportSets.empty()) {
        result.viewportSet = 0;
        return;
    }
    result.viewportSet =
        std::clamp(result.viewportSet, 0, static_cast<int>(p.viewportSets.size()) - 1);
    for (const ViewportSpec& spec : p.viewportSets[result.viewportSet].viewports) {
        ViewportAssignment v;
        v.spec = spec;
        for (const SlotAssignment& slot : result.slotAssignments) {
            if (slot.slot == spec.seriesSlot && slot.seriesIndex >= 0) {
                v.seriesIndex = slot.seriesIndex;
                v.series = &series[slot.seriesIndex];
            }
        }
        result.viewports.push_back(v);
    }
}

HangingResult applyWith(const HangingProtocol& protocol, const std::vector<HangingSeries>& series,
                        int viewportSet, const RankOptions& options, RegexCache& regexes) {
    HangingResult result;
    result.protocol = &protocol;
    result.viewportSet = viewportSet;
    assignSlots(protocol, series, options, regexes, result);
    placeViewports(protocol, series, result);
    // A protocol that would leave its first set empty does not apply.
    if (result.applicable && !protocol.viewportSets.empty() &&
        std::none_of(protocol.viewportSets[0].viewports.begin(),
                     protocol.viewportSets[0].viewports.end(), [&](const ViewportSpec& v) {
                         return std::any_of(
                             result.slotAssignments.begin(), result.slotAssignments.end(),
                             [&](const SlotAssignment& slot) {
                                 return slot.slot == v.seriesSlot && slot.seriesIndex >= 0;
                             });
                     })) {
        result.applicable = false;
        result.reason = "no series for any viewport of its first set";
    }
    return result;
}

} // namespace

const SeriesRule* HangingProtocol::slot(const std::string& slotName) const {
    for (const SeriesRule& rule : seriesSlots) {
        if (rule.name == slotName) {
            return &rule;
        }
    }
    return nullptr;
}

bool HangingProtocol::operator==(const HangingProtocol& o) const {
    return std::tie(name, description, priority, study, seriesSlots, viewportSets) ==
           std::tie(o.name, o.description, o.priority, o.study, o.seriesSlots, o.viewportSets);
}

int HangingResult::filledViewports() const {
    return static_cast<int>(std::count_if(viewports.begin(), viewports.end(),
                                          [](const ViewportAssignment& v) { return v.series; }));
}

std::vector<HangingSeries> orderStudies(std::vector<HangingSeries> series,
                                        const std::string& currentStudyUid) {
    // One entry per study: its patient and the earliest date and time its series give
    // (the series of one study may carry different study times).
    struct Study {
        std::string uid, patientId, date, time;
    };
    std::map<std::string, Study> byUid;
    for (const HangingSeries& s : series) {
        auto [it, added] =
            byUid.try_emplace(s.studyUid, Study{s.studyUid, s.patientId, s.studyDate, s.studyTime});
        Study& study = it->second;
        if (!added && !s.studyDate.empty() &&
            (study.date.empty() ||
             std::tie(s.studyDate, s.studyTime) < std::tie(study.date, study.time))) {
            study.date = s.studyDate;
            study.time = s.studyTime;
        }
    }
    std::vector<Study> newestFirst;
    for (const auto& [uid, study] : byUid) {
        newestFirst.push_back(study);
    }
    // Newest first (an empty date sorts as the oldest), equal dates and times by UID.
    std::sort(newestFirst.begin(), newestFirst.end(), [](const Study& a, const Study& b) {
        return std::tie(b.date, b.time, a.uid) < std::tie(a.date, a.time, b.uid);
    });
    std::map<std::string, int> orders;
    if (!newestFirst.empty()) {
        auto current = std::find_if(newestFirst.begin(), newestFirst.end(),
                                    [&](const Study& s) { return s.uid == currentStudyUid; });
        if (current == newestFirst.end()) {
            current = newestFirst.begin();
        }
        const std::string patient = current->patientId;
        int order = 0;
        for (auto it = current; it != newestFirst.end(); ++it) {
            if (it->patientId == patient) {
                orders[it->uid] = order++;
            }
        }
    }
    for (HangingSeries& s : series) {
        const auto it = orders.find(s.studyUid);
        s.studyOrder = it == orders.end() ? -1 : it->second;
    }
    return series;
}

std::optional<double> scoreSeries(const SeriesRule& rule, const HangingSeries& series) {
    RegexCache regexes;
    return scoreWith(rule, series, regexes, "series '" + rule.name + "'");
}

HangingResult applyProtocol(const HangingProtocol& protocol,
                            const std::vector<HangingSeries>& series, int viewportSet,
                            const RankOptions& options) {
    RegexCache regexes;
    return applyWith(protocol, series, viewportSet, options, regexes);
}

std::vector<HangingResult> rankProtocols(const std::vector<HangingProtocol>& protocols,
                                         const std::vector<HangingSeries>& series,
                                         const RankOptions& options) {
    RegexCache regexes;
    std::vector<HangingResult> results;
    for (const HangingProtocol& p : protocols) {
        results.push_back(applyWith(p, series, 0, options, regexes));
    }
    std::stable_sort(results.begin(), results.end(),
                     [](const HangingResult& a, const HangingResult& b) {
                         return std::make_tuple(!a.applicable, -a.score, -a.filledViewports(),
                                                a.protocol->name, a.protocol->file) <
                                std::make_tuple(!b.applicable, -b.score, -b.filledViewports(),
                                                b.protocol->name, b.protocol->file);
                     });
    return results;
}

const char* viewportViewName(ViewportView view) {
    return nameOf(view, kViewNames).data();
}

const char* criterionName(Criterion criterion) {
    constexpr const char* kNames[kCriterionCount] = {
        "modality",    "bodyPart",  "description", "sliceThickness",
        "orientation", "instances", "kind"};
    return kNames[static_cast<int>(criterion)];
}

} // namespace lucent
