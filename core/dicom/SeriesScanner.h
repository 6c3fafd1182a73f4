#pragma once

#include <string>
#include <vector>

#include "core/io/Catalog.h"

namespace lucent {

// Reads the headers of files (in parallel) and adds their series to the catalog:
// grouped by Series Instance UID, split by orientation, size and image type,
// sorted along the slice normal, with tilt, gaps and duplicates planned for.
void scanDicomFiles(const std::vector<std::string>& files, Catalog& catalog,
                    const LoadControl& control);

} // namespace lucent
