#pragma once
// What the protocol tests ask of a client message's text: the code of the
// ProtocolError it raises.

#include <string>
#include <string_view>

#include "protocol/ProtocolMessages.h"

namespace lucent::remote::test {

// The code of the ProtocolError the text raises, "" when it parses; fatal and the
// message through `fatal` and `message`.
inline std::string errorCode(std::string_view text, bool* fatal = nullptr,
                             int version = kProtocolVersion, std::string* message = nullptr) {
    try {
        parseClientMessage(text, version);
    } catch (const ProtocolError& e) {
        if (fatal) {
            *fatal = e.fatal();
        }
        if (message) {
            *message = e.what();
        }
        return e.code();
    }
    return "";
}

} // namespace lucent::remote::test
