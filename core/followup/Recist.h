#pragma once
// RECIST 1.1 over the timepoints of one patient: tracked lesions by timepoint, the sum of
// diameters, its change from baseline and from the nadir, and the response of each
// follow-up. Plain C++ (no Qt, no DICOM): the store's SRs are gathered elsewhere
// (core/followup/FollowUpCollection.h) into TimepointMeasurements.
//
// The rules, as RECIST 1.1 (Eisenhauer et al., Eur J Cancer 2009) states them and as far as
// a workstation can apply them:
//  - Timepoints are ordered by study date; the first is the baseline. Studies of one date
//    are one timepoint.
//  - A lesion is a measurement marked target or non-target; measurements of one tracking
//    UID are one lesion. Its role, name and lymph-node flag are those of its first
//    timepoint. Two measurements of one lesion at one timepoint: the first counts.
//  - Its diameter (lesionObservationOf): a Distance is the long axis; a Bidirectional gives
//    the long and the short axis; an Ellipse its longer and shorter axis. A lymph node counts
//    by its short axis (a Distance on a node is taken as its short axis). A target lesion
//    pointed at with an Arrow instead of measured counts 0 mm: gone. Angles are not lesions.
//  - The sum of diameters of a timepoint sums the baseline's target lesions measured there.
//    A baseline target lesion not measured at a follow-up makes its response NE (not
//    evaluable), unless the others already show PD.
//  - Change from baseline: (sum - baseline sum) / baseline sum. The nadir of a follow-up is
//    the smallest sum of the evaluable timepoints before it, baseline included; change from
//    the nadir: (sum - nadir) / nadir. Neither when the divisor is 0.
//  - PD: a new lesion (a target or non-target lesion first seen at this follow-up), or a sum
//    at least 20 % over the nadir and at least 5 mm over it. Unequivocal progression of
//    non-target lesions is the reader's judgement and not modelled.
//  - CR: every non-nodal target lesion gone (0 mm) and every nodal target lesion under
//    10 mm short axis; when a baseline non-target lesion is still marked at that follow-up
//    the response is PR (targets CR, non-targets persist: RECIST's table 4).
//  - PR: a sum at least 30 % below the baseline sum.
//  - SD: none of these. With no target lesion at baseline: NE unless PD by a new lesion.
//  Thresholds are compared with a tolerance of 1e-6 mm, so that exactly -30 % is PR and
//  exactly +20 % (and +5 mm) is PD.

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/measure/Measurement.h"

namespace lucent {

// Where a tracked lesion was measured at one timepoint: to go to it.
struct LesionLocation {
    std::string studyDate; // YYYYMMDD
    std::string studyUid;
    std::string seriesUid;
    glm::dvec3 centre{0.0}; // patient LPS mm: the middle of the measurement's points
};

// One tracked lesion as measured at one timepoint.
struct LesionObservation {
    std::string trackingUid;
    std::string name;
    LesionRole role = LesionRole::None;
    bool lymphNode = false;
    double longAxisMm = 0.0;  // 0 when the kind has none
    double shortAxisMm = 0.0; // 0 when the kind has none
    bool gone = false;        // a target lesion pointed at (Arrow), not measured: 0 mm
    double diameterMm = 0.0;  // what RECIST sums: short axis of a node, else long axis
    LesionLocation where;
};

// The observation a measurement makes, or none when it is no lesion (role None, no tracking
// UID, an angle, incomplete).
std::optional<LesionObservation> lesionObservationOf(const Measurement& m,
                                                     const LesionLocation& where);

struct TimepointMeasurements {
    std::string studyDate; // YYYYMMDD
    std::vector<std::string> studyUids;
    std::vector<LesionObservation> lesions;
};

enum class RecistResponse { Baseline, CR, PR, SD, PD, NE };
const char* recistResponseName(RecistResponse r); // "Baseline", "CR", "PR", "SD", "PD", "NE"

struct LesionRow {
    std::string trackingUid;
    std::string name;
    LesionRole role = LesionRole::None;
    bool lymphNode = false;
    std::size_t firstTimepoint = 0;                   // > 0: a new lesion
    std::vector<std::optional<LesionObservation>> at; // one per timepoint; none: not measured
};

struct TimepointAssessment {
    std::string studyDate;
    std::vector<std::string> studyUids;
    double sumMm = 0.0;
    bool evaluable = true; // every baseline target lesion measured
    std::optional<double> nadirMm;
    std::optional<double> fromBaselinePercent;
    std::optional<double> fromNadirPercent;
    RecistResponse response = RecistResponse::Baseline;
    std::vector<std::string> reasons; // why the response, in words
};

struct FollowUpTable {
    std::vector<LesionRow> lesions; // targets first, then non-targets, each by first timepoint
    std::vector<TimepointAssessment> timepoints;
};

// The table of the timepoints (any order; sorted by date here).
FollowUpTable assessRecist(std::vector<TimepointMeasurements> timepoints);

// The lesions first seen before `studyDate` (YYYYMMDD; "" : every lesion), for "same lesion
// as".
std::vector<const LesionRow*> lesionsBefore(const FollowUpTable& table,
                                            const std::string& studyDate);

} // namespace lucent
