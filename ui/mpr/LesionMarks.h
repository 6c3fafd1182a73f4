#pragma once
// Marking a measurement as a RECIST lesion (core/measure LesionTracking): the actions of
// the measurement list's context menu. Each mark is one edit of SeriesMeasurements (one
// undo step, saved by MeasurementAutosave like any other edit).

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/measure/Measurement.h"

class QMenu;

namespace lucent {

class SeriesMeasurements;

// A tracked lesion of the patient's earlier timepoints, offered as "Same lesion as": picking
// it gives the measurement its tracking UID, name, role and lymph-node flag.
struct LesionChoice {
    std::string trackingUid;
    std::string name;
    LesionRole role = LesionRole::Target;
    bool lymphNode = false;
    std::string studyDate; // YYYYMMDD of its first timepoint
};
// The choices for a series (by its UID); FollowUpPanel::earlierLesions is one.
using LesionChoices = std::function<std::vector<LesionChoice>(const std::string& seriesUid)>;

// "Target lesion", "Non-target lesion", "Lymph node (short axis)", "Not a lesion" and the
// "Same lesion as" submenu (choices whose tracking UID another measurement of the series
// already has are left out), added to `menu` for measurement `id`; disabled for a read-only
// measurement and for angles. Object names: lesionTarget, lesionNonTarget, lesionLymphNode,
// lesionNone, lesionSameAs (the submenu; its actions hold the tracking UID as data).
void addLesionActions(QMenu& menu, SeriesMeasurements& measurements, std::uint64_t id,
                      const std::vector<LesionChoice>& earlier);

// "Target", "Target, node", "Non-target", "" : the measurement list's Lesion column.
std::string lesionMarkText(const LesionTracking& lesion);

} // namespace lucent
