#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/hanging/HangingSeries.h"

namespace lucent {

// How a viewport shows its series. Stack: the 2D images as acquired (localizers,
// single images, colour captures, cines).
enum class ViewportView { Axial, Coronal, Sagittal, Oblique, Volume3D, Stack };

// What a rule can test of a series (the study rule: modality, body part, description).
enum class Criterion {
    Modality,
    BodyPart,
    Description,
    SliceThickness,
    Orientation,
    Instances,
    Kind
};
inline constexpr int kCriterionCount = 7;

// How much each criterion counts when it matches, and which must match. A criterion
// that a rule does not set is neither scored nor checked.
struct CriterionScoring {
    std::array<double, kCriterionCount> weight{1, 1, 2, 1, 1, 1, 1}; // description counts 2
    std::array<bool, kCriterionCount> mustMatch{};

    double weightOf(Criterion c) const { return weight[static_cast<int>(c)]; }
    bool mustMatchOf(Criterion c) const { return mustMatch[static_cast<int>(c)]; }
    bool operator==(const CriterionScoring&) const = default;
};

// A study order of a series rule that any study of the patient satisfies (current or prior).
inline constexpr int kAnyStudy = -1;

// One named series slot of a protocol: which series it wants.
struct SeriesRule {
    std::string name;                    // "current", "prior", "lung", ... (unique in its protocol)
    int studyOrder = 0;                  // 0 current, 1 prior 1, ...; kAnyStudy; always enforced
    std::vector<std::string> modalities; // any of (exact, case-insensitive); empty: not tested
    std::string bodyPart;                // ECMAScript regex, searched case-insensitively
    std::string description;             // ECMAScript regex on the series description
    std::optional<double> minSliceThickness, maxSliceThickness; // mm, inclusive
    std::vector<SliceOrientation> orientations;                 // any of
    std::optional<int> minInstances, maxInstances;
    std::vector<SeriesKind> kinds; // any of
    CriterionScoring scoring;
    // The protocol applies only when this slot finds a series (or, before the priors
    // lookup has finished, when its study is not among the series yet).
    bool required = false;
    // A slot that finds no series of its own shows that slot's series ("" none).
    std::string fallback;

    bool operator==(const SeriesRule&) const = default;
};

// What the current study must be for a protocol. bodyPart is searched in every series'
// BodyPartExamined and in the study description (where the element is often empty).
struct StudyRule {
    std::vector<std::string> modalities; // one of the current study's series has one of these
    std::string bodyPart;                // regex
    std::string description;             // regex on the study description
    CriterionScoring scoring;

    bool operator==(const StudyRule&) const = default;
};

struct ViewportSpec {
    int row = 0, column = 0, rowSpan = 1, columnSpan = 1; // cell in the set's grid
    std::string seriesSlot; // the name of a SeriesRule of the protocol
    ViewportView view = ViewportView::Axial;
    // A name of core/mpr/WindowPresets as listed there ("Lung"): findWindowPreset takes
    // it as it is; "" the series' own window.
    std::string windowPreset;
    int linkGroup = 0; // viewports with the same non-zero group scroll and zoom together

    bool operator==(const ViewportSpec&) const = default;
};

// One "stage" of a protocol: a grid of 1x1 up to 4x4 and what each cell shows.
struct ViewportSet {
    std::string name;
    int rows = 1, columns = 1;
    std::vector<ViewportSpec> viewports;

    bool operator==(const ViewportSet&) const = default;
};

struct HangingProtocol {
    std::string name;
    std::string file; // where it was read from (for messages); not written
    std::string description;
    double priority = 0; // added to the score: a fallback protocol ships below zero
    StudyRule study;
    std::vector<SeriesRule> seriesSlots;   // matched in this order, each series to one slot
    std::vector<ViewportSet> viewportSets; // keys step through them

    const SeriesRule* slot(const std::string& slotName) const;
    bool operator==(const HangingProtocol& other) const; // all but `file`
};

// Which series a slot took. seriesIndex: into the series given to the matcher.
struct SlotAssignment {
    std::string slot;
    int seriesIndex = -1;      // -1: none
    double score = 0;          // the series' score for the slot (0 for a fallback)
    bool fromFallback = false; // the series of the slot's fallback
};

struct ViewportAssignment {
    ViewportSpec spec;
    int seriesIndex = -1;                  // into the series given; -1: empty viewport
    const HangingSeries* series = nullptr; // that series (points into the caller's vector)
};

struct HangingResult {
    const HangingProtocol* protocol = nullptr;
    // false: a rule that must match did not, a required slot found no series, or the
    // first viewport set would stay empty (see reason)
    bool applicable = false;
    std::string reason; // why not applicable, in words
    double score = 0;
    int viewportSet = 0;
    std::vector<SlotAssignment> slotAssignments; // one per series slot, in the protocol's order
    std::vector<ViewportAssignment> viewports;   // the set's viewports, in its order
    // Priors the protocol's slots ask for that are not among the series, ascending
    // (the priors fetcher fetches them).
    std::vector<int> missingStudyOrders;

    int filledViewports() const;
};

struct RankOptions {
    // True once every prior the patient has is among the series (the lookup has
    // finished, or the series are all there is, as for lucent-cli): a required slot
    // whose study is absent then makes its protocol inapplicable.
    bool allPriorsPresent = false;
};

// Gives every series its studyOrder: the studies of the current study's patient
// (same PatientID) ordered by study date and time, newest first, then study UID;
// the current one 0 and the older ones 1, 2, ... Newer studies and other patients'
// get -1. An empty currentStudyUid takes the newest study of all. A study's date and
// time are the earliest its series give; a study without a date counts as the oldest.
std::vector<HangingSeries> orderStudies(std::vector<HangingSeries> series,
                                        const std::string& currentStudyUid = {});

// Scores every protocol on the series (their studyOrder set, see orderStudies) and
// returns them best first: applicable before not, then higher score, then more
// viewports filled in the first set, then name, then file. The results point into
// `protocols` and `series`: keep both alive. Throws std::invalid_argument naming the
// protocol and slot on a bad regex (the reader refuses those in files).
std::vector<HangingResult> rankProtocols(const std::vector<HangingProtocol>& protocols,
                                         const std::vector<HangingSeries>& series,
                                         const RankOptions& options = {});

// One protocol's assignment with the viewports of set `viewportSet` (clamped to the
// protocol's sets). The result points into protocol and series.
HangingResult applyProtocol(const HangingProtocol& protocol,
                            const std::vector<HangingSeries>& series, int viewportSet = 0,
                            const RankOptions& options = {});

// The score of one series for one slot, or nullopt when it cannot go there (another
// study order, or a criterion that must match does not).
std::optional<double> scoreSeries(const SeriesRule& rule, const HangingSeries& series);

// Names used in protocol files and messages.
const char* viewportViewName(ViewportView view); // "axial", ..., "3d", "stack"
const char* criterionName(Criterion criterion);  // "modality", "bodyPart", ...

} // namespace lucent
