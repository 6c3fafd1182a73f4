#pragma once

#include "core/io/Catalog.h"
#include "core/stack/ImageStack.h"

namespace lucent {

// Decodes any catalog entry as a 2D image stack, frame after frame in the entry's
// order: colour (RGB, YBR_FULL, YBR_FULL_422, YBR_RCT/ICT through the JPEG 2000
// codec) and palette colour as RGB, MONOCHROME1 and MONOCHROME2 as rescaled grey
// (MONOCHROME1 marked inverted), with each frame's position and the cine timing
// (FrameTime, FrameTimeVector). Volumes load as their slices (never resampled);
// other formats through loadSeries. Compressed frames are decoded in
// lucent-frame-decoder, as for volumes. Throws LoadError naming the file,
// LoadCancelled.
ImageStack loadStack(const SeriesEntry& entry, const LoadControl& control = {});

// The entry's middle frame alone, for thumbnails (one file decoded, not the whole
// cine or series); other formats as loadStack.
ImageStack loadStackPreview(const SeriesEntry& entry, const LoadControl& control = {});

} // namespace lucent
