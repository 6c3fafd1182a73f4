#include "server/UploadParts.h"

#include <algorithm>
#include <cctype>

namespace lucent::remote {
namespace {

std::string lowerCase(std::string_view text) {
    std::string lower(text);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return lower;
}

std::string_view trimmed(std::string_view text) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) {
        text.remove_prefix(1);
    }
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) {
        text.remove_suffix(1);
    }
    return text;
}

// The media type of a Content-Type value (lower case) and one of its parameters.
std::string mediaType(std::string_view contentType) {
    return lowerCase(trimmed(contentType.substr(0, contentType.find(';'))));
}

std::string parameter(std::string_view contentType, std::string_view name) {
    std::size_t at = contentType.find(';');
    while (at != std::string_view::npos) {
        std::string_view rest = contentType.substr(at + 1);
        const std::size_t next = rest.find(';');
        std::string_view item = trimmed(rest.substr(0, next));
        const std::size_t equals = item.find('=');
        if (equals != std::string_view::npos &&
            lowerCase(trimmed(item.substr(0, equals))) == name) {
            std::string_view value = trimmed(item.substr(equals + 1));
            if (value.size() >= 2 && value.front() == '"' && value.back() == '"') {
                value = value.substr(1, value.size() - 2);
            }
            return std::string(value);
        }
        at = next == std::string_view::npos ? next : at + 1 + next;
    }
    return {};
}

} // namespace

std::vector<std::string_view> uploadParts(std::string_view contentType, std::string_view body) {
    const std::string type = mediaType(contentType);
    if (type == "application/dicom") {
        return {body};
    }
    if (type != "multipart/related") {
        throw UploadError(415, "Content-Type '" + std::string(contentType.substr(0, 100)) +
                                   "' is not application/dicom or multipart/related; "
                                   "type=\"application/dicom\"");
    }
    const std::string partType = lowerCase(parameter(contentType, "type"));
    if (!partType.empty() && partType != "application/dicom") {
        throw UploadError(415, "multipart/related: type '" + partType.substr(0, 100) +
                                   "' is not application/dicom");
    }
    const std::string boundary = parameter(contentType, "boundary");
    if (boundary.empty() || boundary.size() > 200) {
        throw UploadError(400, "multipart/related: the Content-Type has no boundary");
    }
    const std::string delimiter = "--" + boundary;
    std::size_t at = body.starts_with(delimiter) ? 0 : body.find("\r\n" + delimiter);
    if (at == std::string_view::npos) {
        throw UploadError(400, "multipart/related: the body holds no boundary '" + boundary + "'");
    }
    at = at == 0 ? delimiter.size() : at + 2 + delimiter.size();
    std::vector<std::string_view> parts;
    while (true) {
        if (body.substr(at).starts_with("--")) {
            break; // the closing delimiter
        }
        const std::size_t headersEnd = body.find("\r\n\r\n", at);
        if (headersEnd == std::string_view::npos) {
            throw UploadError(400, "multipart/related: part " + std::to_string(parts.size() + 1) +
                                       " has no end of its headers");
        }
        const std::string headers = lowerCase(body.substr(at, headersEnd - at));
        const std::size_t typeAt = headers.find("content-type:");
        if (typeAt != std::string::npos) {
            const std::size_t lineEnd = headers.find("\r\n", typeAt);
            const std::string partContentType =
                mediaType(std::string_view(headers).substr(typeAt + 13, lineEnd - typeAt - 13));
            if (partContentType != "application/dicom") {
                throw UploadError(415, "part " + std::to_string(parts.size() + 1) +
                                           ": Content-Type '" + partContentType.substr(0, 100) +
                                           "' is not application/dicom");
            }
        }
        const std::size_t bodyStart = headersEnd + 4;
        const std::size_t next = body.find("\r\n" + delimiter, bodyStart);
        if (next == std::string_view::npos) {
            throw UploadError(400, "multipart/related: part " + std::to_string(parts.size() + 1) +
                                       " is cut short (no closing boundary)");
        }
        parts.push_back(body.substr(bodyStart, next - bodyStart));
        at = next + 2 + delimiter.size();
    }
    if (parts.empty()) {
        throw UploadError(400, "multipart/related: the body holds no part");
    }
    return parts;
}

} // namespace lucent::remote
