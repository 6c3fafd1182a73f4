// Transfer-function presets: resources/presets/<name>.json, found in the
// directories presetDirectories() lists.
#include "core/tf/TransferFunction.h"

#include <algorithm>
#include <cstdlib>
#include <set>
#include <system_error>

namespace lucent {

namespace {

namespace fs = std::filesystem;

// A preset name is a file stem: letters, digits, '-', '_' and '.', not starting with
// '.' (so a name never leaves the preset directory).
bool validName(std::string_view name) {
    if (name.empty() || name.front() == '.') {
        return false;
    }
    return std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
               c == '-' || c == '_' || c == '.';
    });
}

bool isDirectory(const fs::path& path) {
    std::error_code error;
    return fs::is_directory(path, error);
}

std::string join(const std::vector<std::string>& items) {
    std::string result;
    for (const std::string& item : items) {
        result += (result.empty() ? "" : ", ") + item;
    }
    return result.empty() ? "none" : result;
}

} // namespace

std::vector<fs::path> presetDirectories() {
    std::vector<fs::path> candidates;
    if (const char* env = std::getenv("LUCENT_PRESET_DIR"); env && *env) {
        candidates.emplace_back(env);
    }
#ifdef LUCENT_SOURCE_PRESET_DIR
    candidates.emplace_back(LUCENT_SOURCE_PRESET_DIR);
#endif
    std::error_code error;
    const fs::path executable = fs::read_symlink("/proc/self/exe", error);
    if (!error && executable.has_parent_path()) {
        candidates.push_back(executable.parent_path().parent_path() / "share/lucent/presets");
    }
#ifdef LUCENT_INSTALL_PRESET_DIR
    candidates.emplace_back(LUCENT_INSTALL_PRESET_DIR);
#endif
    std::vector<fs::path> result;
    for (const fs::path& candidate : candidates) {
        const fs::path normal = candidate.lexically_normal();
        if (isDirectory(normal) &&
            std::find(result.begin(), result.end(), normal) == result.end()) {
            result.push_back(normal);
        }
    }
    return result;
}

std::vector<std::string> presetNames() {
    std::set<std::string> names;
    for (const fs::path& directory : presetDirectories()) {
        std::error_code error;
        for (fs::directory_iterator it(directory, error), end; !error && it != end;
             it.increment(error)) {
            const fs::path& file = it->path();
            if (file.extension() == ".json" && validName(file.stem().string()) &&
                it->is_regular_file(error)) {
                names.insert(file.stem().string());
            }
        }
    }
    return {names.begin(), names.end()};
}

TransferFunction loadPreset(std::string_view name) {
    const std::vector<fs::path> directories = presetDirectories();
    if (validName(name)) {
        for (const fs::path& directory : directories) {
            const fs::path file = directory / (std::string(name) + ".json");
            std::error_code error;
            if (fs::is_regular_file(file, error)) {
                return readTransferFunction(file);
            }
        }
    }
    std::vector<std::string> searched;
    for (const fs::path& directory : directories) {
        searched.push_back(directory.string());
    }
    throw TransferFunctionError("unknown transfer-function preset '" + std::string(name) +
                                "'; the known presets are " + join(presetNames()) +
                                " (searched: " + join(searched) + ")");
}

} // namespace lucent
