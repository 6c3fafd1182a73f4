#pragma once
// Work that every rank does before the next collective, and a failure on any
// rank that every rank learns of: no rank waits in a collective for one that
// threw, and the message names the rank and the cause.

#include <functional>
#include <stdexcept>
#include <string>

#include "render/distributed/Communicator.h"

namespace lucent {

// A failure of one or more ranks, as every rank reports it: "rank R: cause"
// for each rank that failed, joined by "; ".
class DistributedError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Runs `work` on this rank, then (collectively) learns whether it threw on any
// rank; throws DistributedError naming those ranks and their messages on
// every rank when one did. `what` says what was being done ("reading the
// part").
void onEveryRank(const Communicator& comm, const std::string& what,
                 const std::function<void()>& work);

} // namespace lucent
