#include "core/segmentation/SegmentStatisticsCsv.h"

#include <cmath>
#include <cstdio>

namespace lucent {
namespace {

std::string number(double value) {
    if (std::isnan(value)) {
        return {};
    }
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", value);
    return text;
}

std::string field(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) {
        return text;
    }
    std::string quoted = "\"";
    for (const char c : text) {
        quoted += c;
        if (c == '"') {
            quoted += '"';
        }
    }
    return quoted + '"';
}

} // namespace

std::string statisticsCsv(const std::vector<NamedStatistics>& rows) {
    std::string csv = "segment,voxels,volume_ml,mean,sd,min,max,median,surface_area_cm2,"
                      "largest_diameter_mm\r\n";
    for (const NamedStatistics& row : rows) {
        const SegmentStatistics& s = row.statistics;
        csv += field(row.name) + ',' + std::to_string(s.voxels);
        for (const double v : {s.volumeMl, s.mean, s.standardDeviation, s.minimum, s.maximum,
                               s.median, s.surfaceAreaCm2, s.largestDiameterMm}) {
            csv += ',' + number(v);
        }
        csv += "\r\n";
    }
    return csv;
}

} // namespace lucent
