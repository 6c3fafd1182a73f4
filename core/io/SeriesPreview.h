#pragma once
// One image of a series, for thumbnails: the middle image of a DICOM stack
// (one file decoded, not the whole series), or the whole volume for the
// single-file formats.

#include "core/io/Catalog.h"

namespace lucent {

// A one-slice volume (DICOM) in the slice's own plane and position, rescaled
// like the full load. Throws LoadError naming the file, LoadCancelled.
Volume loadPreviewImage(const SeriesEntry& entry, const LoadControl& control = {});

} // namespace lucent
