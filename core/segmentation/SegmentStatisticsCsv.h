#pragma once
// The Segments panel's statistics table as CSV (RFC 4180): one row per segment.

#include <string>
#include <vector>

#include "core/segmentation/SegmentStatistics.h"

namespace lucent {

struct NamedStatistics {
    std::string name;
    SegmentStatistics statistics;
};

// Header: segment,voxels,volume_ml,mean,sd,min,max,median,surface_area_cm2,
// largest_diameter_mm (values in the volume's unit, HU for CT); a value the segment has not
// (an empty one) is left empty; numbers with 17 significant digits, so that they read back
// exactly; a name with a comma, quote or line break is quoted.
std::string statisticsCsv(const std::vector<NamedStatistics>& rows);

} // namespace lucent
