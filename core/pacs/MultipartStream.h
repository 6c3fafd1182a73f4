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

    // Throws PacsError naming `where` when the content type has no boundary (or
    // an empty one).
    MultipartStream(const QByteArray& contentType, std::string where);

    // Throws PacsError when a part's delimiter line or headers run past
    // maxHeaderBytes. Bytes after the closing delimiter are ignored.
    void feed(const char* data, qsizetype size);
    // At the end of the body: throws PacsError when the last part is cut short.
    void finish() const;
    int parts() const { return parts_; }

    static constexpr qsizetype maxHeaderBytes = 64 * 1024;

private:
    enum class State { Preamble, Delimiter, Headers, Body, Done };
    bool step(); // false when it needs more bytes
    // Where `terminator` ends a line of the part's head, or -1 while more bytes
    // are needed; throws when it lies past maxHeaderBytes (whatever the
    // chunking).
    qsizetype headEnd(const char* terminator, const char* what) const;

    std::string where_;
    QByteArray delimiter_; // CRLF "--" boundary
    QByteArray buffer_;
    qsizetype pos_ = 0; // consumed bytes of buffer_
    State state_ = State::Preamble;
    bool openingChecked_ = false; // whether the body's first bytes were the first delimiter
    int parts_ = 0;
};

} // namespace lucent
