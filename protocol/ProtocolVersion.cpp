#include "protocol/ProtocolVersion.h"

#include <charconv>

namespace lucent::remote {
namespace {

constexpr std::string_view kPrefix = "lucent.v";

} // namespace

std::string subprotocolName(int version) {
    return std::string(kPrefix) + std::to_string(version);
}

std::optional<int> subprotocolVersion(std::string_view name) {
    if (!name.starts_with(kPrefix)) {
        return std::nullopt;
    }
    const std::string_view digits = name.substr(kPrefix.size());
    int version = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), version);
    if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty() ||
        digits.front() == '0' || version < kOldestProtocolVersion || version > kProtocolVersion) {
        return std::nullopt;
    }
    return version;
}

std::vector<std::string> supportedSubprotocols() {
    std::vector<std::string> names;
    for (int v = kProtocolVersion; v >= kOldestProtocolVersion; --v) {
        names.push_back(subprotocolName(v));
    }
    return names;
}

} // namespace lucent::remote
