#pragma once
// A series loaded as the workstation shows it: the one place where the main window's loader
// and the viewport grid's sessions turn decoded voxels into the values a reader sees.

#include "core/io/LoadControl.h"
#include "core/io/SeriesEntry.h"

namespace lucent {

// loadSeries, and for a DICOM PET series (modality PT) its values in SUVbw
// (core/pet/SuvStatistics.h: petVolumeForDisplay) when the headers of all its files give a
// factor; else as stored, with the reason in volume.pet->refusal (a header that cannot be
// read is such a reason too, never an exception). Throws what loadSeries throws.
Volume loadDisplayedSeries(const SeriesEntry& entry, const LoadControl& control = {});

} // namespace lucent
