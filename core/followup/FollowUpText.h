#pragma once
// The follow-up table as text, one home for every place that shows it: the panel's cells,
// the CSV export and `lucent-cli measurements --recist`. Plain C++.

#include <string>
#include <vector>

#include "core/followup/Recist.h"
#include "core/volume/SeriesInfo.h" // formatStudyDate

namespace lucent {

// "+25.0 %", "-30.0 %"; "" for none.
std::string formatPercent(const std::optional<double>& percent);
// A lesion at one timepoint: "23.4" (mm, the diameter RECIST sums), "0 (gone)",
// "present" for a non-target lesion, "" when not measured there.
std::string formatLesionCell(const LesionRow& row, const std::optional<LesionObservation>& o);
// "Target", "Target, lymph node", "Non-target".
std::string formatLesionRole(const LesionRow& row);

// The table as a grid of cells: the header row ("Lesion", "Role", then each timepoint's
// date), one row per lesion (table.lesions in order), then the rows "Sum of diameters (mm)",
// "Change from baseline", "Change from nadir", "Response" and "Reason".
struct FollowUpGrid {
    static constexpr std::size_t kLabelColumns = 2; // lesion name, role
    std::vector<std::vector<std::string>> rows;
};
FollowUpGrid followUpGrid(const FollowUpTable& table);

// The grid as CSV (RFC 4180: commas, quotes doubled, CRLF line ends).
std::string followUpCsv(const FollowUpTable& table);
// The grid as aligned plain text, for a terminal.
std::string followUpText(const FollowUpTable& table);

} // namespace lucent
