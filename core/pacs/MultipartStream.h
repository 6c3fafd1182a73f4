#pragma once
// An incremental multipart/related parser (RFC 2046): bytes go in as they
// arrive, each part's body comes out in pieces, so a WADO-RS series is written
// to disk while it downloads. Private to lucent_pacs.

#include <functional>
#include <string>

#include <QByteArray>

namespace lucent {

class MultipartStream {
public:
    std::function<void()> onPartBegin;
    std::function<void(const char* data, qsizetype size)> onPartData;
    std::function<void()> onPartEnd;

    // Throws PacsError naming `where` when the content type has no boundary.
    MultipartStream(const QByteArray& contentType, std::string where);

    void feed(const char* data, qsizetype size);
    // At the end of the body: throws PacsError when the last part is cut short.
    void finish() const;
    int parts() const { return parts_; }

private:
    enum class State { Preamble, Delimiter, Headers, Body, Done };
    bool step(); // false when it needs more bytes

    std::string where_;
    QByteArray delimiter_; // CRLF "--" boundary
    QByteArray buffer_;
    qsizetype pos_ = 0; // consumed bytes of buffer_
    State state_ = State::Preamble;
    int parts_ = 0;
};

} // namespace lucent
