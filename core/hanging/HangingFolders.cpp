// Where protocol files are: the shipped defaults and the user's folder (one place for both
// the workstation and lucent-cli).
#include "core/hanging/HangingProtocolJson.h"

#include <algorithm>
#include <cstdlib>

namespace lucent {

std::vector<std::filesystem::path> shippedHangingFolders() {
    namespace fs = std::filesystem;
    std::vector<fs::path> candidates;
    if (const char* env = std::getenv("LUCENT_HANGING_DIR"); env && *env) {
        candidates.emplace_back(env);
    }
#ifdef LUCENT_SOURCE_HANGING_DIR
    candidates.emplace_back(LUCENT_SOURCE_HANGING_DIR);
#endif
    std::error_code error;
    const fs::path executable = fs::read_symlink("/proc/self/exe", error);
    if (!error && executable.has_parent_path()) {
        candidates.push_back(executable.parent_path().parent_path() / "share/lucent/hanging");
    }
#ifdef LUCENT_INSTALL_HANGING_DIR
    candidates.emplace_back(LUCENT_INSTALL_HANGING_DIR);
#endif
    std::vector<fs::path> result;
    for (const fs::path& candidate : candidates) {
        const fs::path normal = candidate.lexically_normal();
        if (fs::is_directory(normal, error) &&
            std::find(result.begin(), result.end(), normal) == result.end()) {
            result.push_back(normal);
        }
    }
    return result;
}

std::filesystem::path userHangingFolder(const std::filesystem::path& dataHome) {
    return dataHome / "lucent" / "hanging";
}

std::vector<std::filesystem::path> hangingFolders(const std::filesystem::path& userFolder) {
    std::vector<std::filesystem::path> folders{userFolder};
    for (const std::filesystem::path& shipped : shippedHangingFolders()) {
        folders.push_back(shipped);
    }
    return folders;
}

} // namespace lucent
