#include "core/pacs/PacsNode.h"

#include <charconv>

namespace lucent {

std::string PacsNode::describe() const {
    return aeTitle + "@" + host + ":" + std::to_string(port);
}

void checkAeTitle(std::string_view title, std::string_view what) {
    const auto blank = title.find_first_not_of(' ') == std::string_view::npos;
    if (title.empty() || title.size() > 16 || blank) {
        throw PacsError(std::string(what) + " '" + std::string(title) +
                        "' is not an AE title (1 to 16 characters)");
    }
    for (const char c : title) {
        if (c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
            throw PacsError(std::string(what) + " '" + std::string(title) +
                            "' holds a backslash or a control character");
        }
    }
}

PacsNode PacsNode::parse(std::string_view spec) {
    const std::size_t at = spec.find('@');
    const std::size_t colon = spec.rfind(':');
    if (at == std::string_view::npos || colon == std::string_view::npos || colon < at) {
        throw PacsError("PACS '" + std::string(spec) + "' is not of the form AET@HOST:PORT");
    }
    PacsNode node;
    node.aeTitle = std::string(spec.substr(0, at));
    node.host = std::string(spec.substr(at + 1, colon - at - 1));
    checkAeTitle(node.aeTitle, "PACS AE title");
    if (node.host.empty()) {
        throw PacsError("PACS '" + std::string(spec) + "' has no host");
    }
    const std::string_view port = spec.substr(colon + 1);
    int value = 0;
    const auto [ptr, ec] = std::from_chars(port.data(), port.data() + port.size(), value);
    if (ec != std::errc() || ptr != port.data() + port.size() || value < 1 || value > 65535) {
        throw PacsError("PACS port '" + std::string(port) + "' is not a number from 1 to 65535");
    }
    node.port = value;
    return node;
}

} // namespace lucent
