// What both senders share: counting outcomes.
#include "core/pacs/InstanceSender.h"

#include <algorithm>

namespace lucent {

int SendResult::count(SentInstance::Outcome o) const {
    return static_cast<int>(std::count_if(instances.begin(), instances.end(),
                                          [o](const SentInstance& s) { return s.outcome == o; }));
}

bool SendResult::allStored() const {
    return std::all_of(instances.begin(), instances.end(), [](const SentInstance& s) {
        return s.outcome == SentInstance::Outcome::Stored ||
               s.outcome == SentInstance::Outcome::StoredWithWarning;
    });
}

const char* outcomeName(SentInstance::Outcome o) {
    switch (o) {
    case SentInstance::Outcome::Stored:
        return "stored";
    case SentInstance::Outcome::StoredWithWarning:
        return "stored with warning";
    case SentInstance::Outcome::Failed:
        return "failed";
    case SentInstance::Outcome::NotSent:
        return "not sent";
    }
    return "?";
}

} // namespace lucent
