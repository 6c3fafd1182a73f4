#pragma once
// Compares secrets (tokens, invite digests) byte by byte without stopping at
// the first difference: the time says nothing about the contents (the length
// is not secret).

#include <cstddef>
#include <string_view>

namespace lucent::remote {

inline bool equalInConstantTime(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) {
        return false;
    }
    unsigned difference = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        difference |= static_cast<unsigned char>(a[i]) ^ static_cast<unsigned char>(b[i]);
    }
    return difference == 0;
}

} // namespace lucent::remote
