#include "protocol/ClientMessages.h"

namespace lucent::remote {
namespace {

// Every type, in the variant's order, with the version that brought it.
struct TypeInfo {
    std::string_view type;
    int version = 1;
    bool view = false;
};
constexpr TypeInfo kTypes[] = {
    {"auth", 1, false},
    {"list", 1, false},
    {"open", 1, false},
    {"camera", 1, true},
    {"tf", 1, true},
    {"mode", 1, true},
    {"clip", 1, true},
    {"quality", 1, true},
    {"sampling", 2, true},
    {"size", 1, true},
    {"render", 1, true},
    {"interaction", 1, true},
    {"session-create", 1, false},
    {"session-join", 1, false},
    {"session-handover", 1, false},
    {"session-leave", 1, false},
    {"invite-create", 3, false},
    {"invite-revoke", 3, false},
    {"pointer", 4, false},
    {"mark", 4, false},
    {"marks-clear", 4, false},
    {"free-look", 4, false},
    {"free-look-recall", 4, false},
    {"slices", 4, false},
    {"record", 4, false},
    {"recording-list", 4, false},
    {"replay", 4, false},
    {"replay-step", 4, false},
    {"replay-stop", 4, false},
};
static_assert(std::size(kTypes) == std::variant_size_v<ClientMessage>);

const TypeInfo& info(const ClientMessage& message) {
    return kTypes[message.index()];
}

} // namespace

const char* qualityName(Quality quality) {
    return quality == Quality::Interactive ? "interactive" : "still";
}

const char* replayPaceName(ReplayPace pace) {
    return pace == ReplayPace::Step ? "step" : "original";
}

bool isViewMessage(const ClientMessage& message) {
    return info(message).view;
}

std::string_view messageType(const ClientMessage& message) {
    return info(message).type;
}

int messageTypeVersion(std::string_view type) {
    for (const TypeInfo& t : kTypes) {
        if (t.type == type) {
            return t.version;
        }
    }
    return 0;
}

int messageVersion(const ClientMessage& message) {
    return info(message).version;
}

} // namespace lucent::remote
