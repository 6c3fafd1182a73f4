// fuzz_protocol: one input is one WebSocket message. It is read as a client's
// text message in every protocol version, as a server's text message, and as a
// binary frame message. Refusals are ProtocolErrors; what is accepted must
// survive its writer: written and read again, it is the same message.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "protocol/ClientMessageJson.h"
#include "protocol/FrameMessage.h"
#include "protocol/ServerMessages.h"

namespace {

[[noreturn]] void roundTripFailed(const char* what, const std::string& written) {
    std::fprintf(stderr, "fuzz_protocol: %s does not read back as itself: %s\n", what,
                 written.c_str());
    std::abort();
}

void clientMessage(std::string_view text, int version) {
    using namespace lucent::remote;
    ClientMessage message;
    try {
        message = parseClientMessage(text, version);
    } catch (const ProtocolError&) {
        return;
    }
    const std::string written = writeClientMessage(message);
    if (!(parseClientMessage(written, version) == message)) {
        roundTripFailed("a client message", written);
    }
}

void serverMessage(std::string_view text) {
    using namespace lucent::remote;
    ServerMessage message;
    try {
        message = parseServerMessage(text);
    } catch (const ProtocolError&) {
        return;
    }
    const std::string written = writeServerMessage(message);
    if (!(parseServerMessage(written) == message)) {
        roundTripFailed("a server message", written);
    }
}

void frameMessage(std::string_view bytes) {
    using namespace lucent::remote;
    ParsedFrame frame;
    try {
        frame = parseFrameMessage(bytes);
    } catch (const ProtocolError&) {
        return;
    }
    const std::string written = lucent::remote::frameMessage(frame.header, frame.image);
    const ParsedFrame again = parseFrameMessage(written);
    if (!(again.header == frame.header) || again.image != frame.image) {
        roundTripFailed("a frame header", written.substr(0, written.size() - frame.image.size()));
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    for (int version = lucent::remote::kOldestProtocolVersion;
         version <= lucent::remote::kProtocolVersion; ++version) {
        clientMessage(input, version);
    }
    serverMessage(input);
    frameMessage(input);
    return 0;
}
