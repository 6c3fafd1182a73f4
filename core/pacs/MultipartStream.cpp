#include "core/pacs/MultipartStream.h"

#include "core/pacs/PacsNode.h"

namespace lucent {

MultipartStream::MultipartStream(const QByteArray& contentType, std::string where)
    : where_(std::move(where)) {
    const qsizetype b = contentType.indexOf("boundary=");
    if (!contentType.trimmed().toLower().startsWith("multipart/") || b < 0) {
        throw PacsError(where_ + ": the answer is not multipart/related with a boundary (" +
                        contentType.toStdString() + ")");
    }
    QByteArray boundary = contentType.mid(b + 9);
    const qsizetype semicolon = boundary.indexOf(';');
    if (semicolon >= 0) {
        boundary = boundary.left(semicolon);
    }
    boundary = boundary.trimmed();
    if (boundary.startsWith('"') && boundary.size() >= 2) {
        boundary = boundary.mid(1, boundary.size() - 2);
    }
    if (boundary.isEmpty()) { // RFC 2046: 1 to 70 characters
        throw PacsError(where_ + ": the answer's multipart boundary is empty (" +
                        contentType.toStdString() + ")");
    }
    delimiter_ = "\r\n--" + boundary;
}

void MultipartStream::feed(const char* data, qsizetype size) {
    if (state_ == State::Done) {
        return; // the epilogue
    }
    buffer_.append(data, size);
    while (state_ != State::Done && step()) {
    }
    buffer_.remove(0, pos_); // keeps only a tail shorter than the delimiter
    pos_ = 0;
}

bool MultipartStream::step() {
    const qsizetype available = buffer_.size() - pos_;
    switch (state_) {
    case State::Preamble: {
        // The first delimiter may open the body, without the CRLF before it: only
        // at the body's very start (pos_ moves on once that is decided).
        const QByteArrayView first = QByteArrayView(delimiter_).sliced(2);
        if (!openingChecked_ && available >= first.size()) {
            openingChecked_ = true;
            if (QByteArrayView(buffer_).sliced(pos_).startsWith(first)) {
                pos_ += first.size();
                state_ = State::Delimiter;
                return true;
            }
        }
        const qsizetype at = buffer_.indexOf(delimiter_, pos_);
        if (at < 0) {
            pos_ = std::max(pos_, buffer_.size() - delimiter_.size());
            return false;
        }
        pos_ = at + delimiter_.size();
        state_ = State::Delimiter;
        return true;
    }
    case State::Delimiter: {
        if (available < 2) {
            return false;
        }
        if (buffer_[pos_] == '-' && buffer_[pos_ + 1] == '-') {
            state_ = State::Done; // the closing delimiter
            pos_ = buffer_.size();
            return false;
        }
        const qsizetype eol = headEnd("\r\n", "delimiter line");
        if (eol < 0) {
            return false;
        }
        pos_ = eol + 2;
        state_ = State::Headers;
        return true;
    }
    case State::Headers: {
        qsizetype bodyStart = -1;
        if (available >= 2 && buffer_[pos_] == '\r' && buffer_[pos_ + 1] == '\n') {
            bodyStart = pos_ + 2; // a part without headers
        } else if (const qsizetype end = headEnd("\r\n\r\n", "headers"); end >= 0) {
            bodyStart = end + 4;
        }
        if (bodyStart < 0) {
            return false;
        }
        pos_ = bodyStart;
        state_ = State::Body;
        ++parts_;
        if (onPartBegin) {
            onPartBegin();
        }
        return true;
    }
    case State::Body: {
        const qsizetype at = buffer_.indexOf(delimiter_, pos_);
        const qsizetype end = at >= 0 ? at : buffer_.size() - delimiter_.size() + 1;
        if (end > pos_ && onPartData) {
            onPartData(buffer_.constData() + pos_, end - pos_);
        }
        pos_ = std::max(pos_, end);
        if (at < 0) {
            return false;
        }
        pos_ = at + delimiter_.size();
        state_ = State::Delimiter;
        if (onPartEnd) {
            onPartEnd();
        }
        return true;
    }
    case State::Done:
        return false;
    }
    return false;
}

qsizetype MultipartStream::headEnd(const char* terminator, const char* what) const {
    const QByteArrayView t(terminator);
    const qsizetype at = buffer_.indexOf(t, pos_);
    if (at >= 0 && at - pos_ <= maxHeaderBytes) {
        return at;
    }
    if (buffer_.size() - pos_ >= maxHeaderBytes + t.size()) {
        throw PacsError(where_ + ": the " + what + " of part " + std::to_string(parts_ + 1) +
                        " run past " + std::to_string(maxHeaderBytes / 1024) + " KiB");
    }
    return -1;
}

void MultipartStream::finish() const {
    if (state_ != State::Done && (state_ != State::Preamble || parts_ > 0)) {
        throw PacsError(where_ + ": the multipart answer ends in the middle of part " +
                        std::to_string(parts_) + " (connection lost?)");
    }
}

} // namespace lucent
