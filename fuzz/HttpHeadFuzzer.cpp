// fuzz_http_head: one input is what a client sends the front door before its
// body. As HttpFrontDoor::onReadable does, the head is what precedes the first
// empty line (at most kMaxRequestHeadBytes); it is parsed, and an accepted head
// is asked what the front door asks it (upgrade, the fields of an upload).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include <QByteArray>

#include "server/HttpRequestHead.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace lucent::remote;
    const QByteArray received =
        QByteArray::fromRawData(reinterpret_cast<const char*>(data), static_cast<qsizetype>(size));
    const qsizetype end = received.indexOf("\r\n\r\n");
    const QByteArray head = end < 0 ? received : received.left(end + 4);
    const std::optional<HttpRequestHead> request = parseHttpRequestHead(head);
    if (!request) {
        return 0;
    }
    if (request->method.isEmpty() || !request->target.startsWith('/')) {
        std::fprintf(stderr, "fuzz_http_head: accepted a head without a method or a path\n");
        std::abort();
    }
    (void)request->isWebSocketUpgrade();
    for (const char* name : {"content-length", "content-type", "authorization", "expect",
                             "transfer-encoding", "upgrade"}) {
        (void)request->field(name).toLongLong();
    }
    return 0;
}
