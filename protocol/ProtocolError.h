#pragma once
// Why a message was refused or cannot be read. `code` is one of the error codes
// of docs/protocol.md; a fatal error ends the connection after it is sent.

#include <stdexcept>
#include <string>

namespace lucent::remote {

class ProtocolError : public std::runtime_error {
public:
    ProtocolError(std::string code, const std::string& message, bool fatal)
        : std::runtime_error(message), code_(std::move(code)), fatal_(fatal) {}
    const std::string& code() const { return code_; }
    bool fatal() const { return fatal_; }

private:
    std::string code_;
    bool fatal_;
};

// A field missing, of the wrong type or out of range (not fatal).
[[noreturn]] inline void throwBadRequest(const std::string& message) {
    throw ProtocolError("bad-request", message, false);
}

} // namespace lucent::remote
