#pragma once
// The copy of a series that a teaching session shows: DICOM files
// de-identified (PS3.15 Annex E basic profile, core/dicom/Deidentifier.h) into
// DIR/deidentified/<new uid>/ under the server's store; volume files (which
// hold no patient attributes) under a new id, without description or names.

#include <filesystem>
#include <memory>

#include "core/io/SeriesEntry.h"

namespace lucent::remote {

// Blocking (reads and writes every file of the series). Throws
// DeidentifyError or LoadError.
std::shared_ptr<const SeriesEntry> makeDeidentifiedCopy(const SeriesEntry& original,
                                                        const std::filesystem::path& storeDir);

} // namespace lucent::remote
