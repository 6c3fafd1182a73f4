#include "core/volume/SeriesInfo.h"

#include <algorithm>

namespace lucent {

std::string formatStudyDate(const std::string& d) {
    const bool digits = d.size() == 8 && std::all_of(d.begin(), d.end(),
                                                     [](char c) { return c >= '0' && c <= '9'; });
    return digits ? d.substr(0, 4) + "-" + d.substr(4, 2) + "-" + d.substr(6, 2) : d;
}

} // namespace lucent
