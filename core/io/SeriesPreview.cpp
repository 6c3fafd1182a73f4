#include "core/io/SeriesPreview.h"

namespace lucent {

Volume loadPreviewImage(const SeriesEntry& entry, const LoadControl& control) {
    if (entry.format != SourceFormat::Dicom || entry.slices.size() <= 1) {
        return loadSeries(entry, control);
    }
    // The middle image as a stack of one: its own position, no resampling
    // (a tilted or uneven stack resamples across slices, which one image has not).
    SeriesEntry one = entry;
    const SliceRef middle = entry.slices[entry.slices.size() / 2];
    one.slices = {middle};
    one.resampled = false;
    one.geometry.dims = {entry.pixels.columns, entry.pixels.rows, 1};
    one.geometry.origin = middle.position;
    return loadSeries(one, control);
}

} // namespace lucent
