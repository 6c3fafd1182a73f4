#pragma once
// What a Spatial Registration object says about two series on disk: each DICOM series
// with its instances' SOP UIDs (read from its files) and the fixed series' patient and
// study. Shared by lucent-cli register --sro and the workstation's "Save Registrations".

#include <glm/glm.hpp>

#include "core/exchange/SpatialRegistrationWriter.h"
#include "core/io/Catalog.h"

namespace lucent {

// Throws std::runtime_error naming the series when it is not DICOM (no SOP instances to
// refer to) and LoadError when a file's header cannot be read.
RegisteredSeries registeredSeriesOf(const SeriesEntry& entry);

// The writer's input for fixed -> moving: both series, the fixed one's patient and study.
SpatialRegistrationInput spatialRegistrationInput(const SeriesEntry& fixed,
                                                  const SeriesEntry& moving,
                                                  const glm::dmat4& fixedToMoving);

} // namespace lucent
