// StudyStore's one home for "no space": the reserve kept for the index and
// the error a full file system gives.
#include "core/store/StudyStore.h"

#include <system_error>

namespace lucent {

namespace fs = std::filesystem;

void StudyStore::requireSpace(std::uintmax_t bytes) const {
    std::error_code ec;
    const fs::space_info space = fs::space(root_, ec);
    if (ec) {
        return; // unknown: the write itself will tell
    }
    if (space.available < bytes + kSpaceReserveBytes) {
        const std::string need = bytes > 0
                                     ? "an instance of " + std::to_string((bytes + 1023) / 1024) +
                                           " KiB needs that plus the "
                                     : "less than the ";
        throw StoreError(root_.string() + ": no space left on the store's file system (" +
                         std::to_string(space.available / 1024) + " KiB free, " + need +
                         std::to_string(kSpaceReserveBytes / 1024) +
                         " KiB kept for the index); nothing half-written was kept");
    }
}

StoreError StudyStore::writeError(const fs::path& file, const std::string& cause) const {
    try {
        requireSpace(0);
    } catch (const StoreError& full) {
        return StoreError(full.what() + std::string(" (writing ") + file.filename().string() +
                          ": " + cause + ")");
    }
    return StoreError(cause);
}

} // namespace lucent
