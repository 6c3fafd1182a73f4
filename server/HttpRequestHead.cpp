#include "server/HttpRequestHead.h"

#include <QRegularExpression>
#include <QString>

namespace lucent::remote {

QByteArray HttpRequestHead::field(const QByteArray& lowerCaseName) const {
    for (const auto& [name, value] : fields) {
        if (name == lowerCaseName) {
            return value;
        }
    }
    return {};
}

bool HttpRequestHead::isWebSocketUpgrade() const {
    for (const QByteArray& token : field("upgrade").split(',')) {
        if (token.trimmed().toLower() == "websocket") {
            return true;
        }
    }
    return false;
}

std::optional<HttpRequestHead> parseHttpRequestHead(const QByteArray& head) {
    if (!head.endsWith("\r\n\r\n")) {
        return std::nullopt;
    }
    const QList<QByteArray> lines = head.left(head.size() - 4).split('\n');
    const QList<QByteArray> requestLine = lines.front().trimmed().split(' ');
    if (requestLine.size() != 3) {
        return std::nullopt;
    }
    HttpRequestHead request{requestLine[0], requestLine[1], requestLine[2], {}};
    static const QRegularExpression method("^[A-Z]{1,16}$");
    if (!method.match(QString::fromLatin1(request.method)).hasMatch() ||
        !request.target.startsWith('/') ||
        (request.version != "HTTP/1.1" && request.version != "HTTP/1.0")) {
        return std::nullopt;
    }
    for (qsizetype n = 1; n < lines.size(); ++n) {
        const QByteArray& line = lines[n];
        const qsizetype colon = line.indexOf(':');
        if (!line.endsWith('\r') && n + 1 < lines.size()) {
            return std::nullopt; // a bare LF inside the head
        }
        if (colon <= 0 || line.front() == ' ' || line.front() == '\t' ||
            line.left(colon).contains(' ')) {
            return std::nullopt; // no name, or an obsolete folded line
        }
        request.fields.append({line.left(colon).toLower(), line.mid(colon + 1).trimmed()});
    }
    return request;
}

} // namespace lucent::remote
