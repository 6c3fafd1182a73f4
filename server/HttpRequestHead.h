#pragma once
// The head of an HTTP/1.x request as the front door (HttpFrontDoor.h) reads it:
// request line and header fields. Pure parsing, no sockets: the fuzz harness
// (fuzz/HttpFuzzer.cpp) calls it as the front door does.

#include <QByteArray>
#include <QList>
#include <QPair>

#include <optional>

namespace lucent::remote {

// The head of an HTTP/1.x request: request line and header fields.
struct HttpRequestHead {
    QByteArray method;
    QByteArray target; // as sent: path and query
    QByteArray version;
    QList<QPair<QByteArray, QByteArray>> fields; // names lower-cased, values trimmed

    QByteArray field(const QByteArray& lowerCaseName) const;
    bool isWebSocketUpgrade() const;
};

// Parses a request head that ends with an empty line; nullopt when it is not HTTP/1.x.
std::optional<HttpRequestHead> parseHttpRequestHead(const QByteArray& head);

} // namespace lucent::remote
