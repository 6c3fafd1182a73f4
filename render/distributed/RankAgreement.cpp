#include "render/distributed/RankAgreement.h"

#include <new>
#include <vector>

namespace lucent {

void onEveryRank(const Communicator& comm, const std::string& what,
                 const std::function<void()>& work) {
    std::string failure;
    try {
        work();
    } catch (const std::bad_alloc&) {
        failure = "out of memory";
    } catch (const std::exception& e) {
        failure = e.what();
        if (failure.empty()) {
            failure = "failed";
        }
    } catch (...) {
        failure = "an unknown exception";
    }
    const std::span<const std::byte> mine(reinterpret_cast<const std::byte*>(failure.data()),
                                          failure.size());
    const std::vector<std::vector<std::byte>> all = comm.allGather(mine);
    std::string message;
    for (std::size_t r = 0; r < all.size(); ++r) {
        if (all[r].empty()) {
            continue;
        }
        if (!message.empty()) {
            message += "; ";
        }
        message += "rank " + std::to_string(r) + ": " + what + ": " +
                   std::string(reinterpret_cast<const char*>(all[r].data()), all[r].size());
    }
    if (!message.empty()) {
        throw DistributedError(message);
    }
}

} // namespace lucent
