#pragma once
// A folder's files into a new ZIP file (libzip, deflated), names relative to
// the folder with '/' separators. Private to lucent_exchange.

#include <filesystem>

namespace lucent {

// Throws ExportError naming the ZIP file or the file that could not be added.
void zipFolder(const std::filesystem::path& folder, const std::filesystem::path& zipFile);

} // namespace lucent
