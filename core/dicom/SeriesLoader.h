#pragma once

#include "core/io/Catalog.h"

namespace lucent {

// Decodes the slices of a DICOM entry in parallel (uncompressed data read
// straight from the files, everything else through GDCM), rescales them and,
// when the entry says so, resamples them onto its rectilinear grid.
Volume loadDicomSeries(const SeriesEntry& entry, const LoadControl& control);

} // namespace lucent
