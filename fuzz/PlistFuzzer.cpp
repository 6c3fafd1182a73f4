// fuzz_plist: one input is an XML property list, as main.plist of an InVesalius
// project; parsePlist (libplist underneath) reads it straight, without the tar
// around it that fuzz_inv3 has to keep intact. The only refusal is the
// std::runtime_error saying what is wrong; whatever is accepted must stay within
// the nesting limit.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

#include "core/formats/Plist.h"

namespace {

int depthOf(const lucent::formats::PlistValue& v) {
    int deepest = 0;
    for (const auto& item : v.items) {
        const int d = depthOf(item) + 1;
        deepest = d > deepest ? d : deepest;
    }
    return deepest;
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        const auto root = lucent::formats::parsePlist(
            std::string_view(reinterpret_cast<const char*>(data), size));
        if (root.keys.size() > root.items.size() ||
            depthOf(root) > lucent::formats::maxPlistDepth) {
            std::fprintf(stderr, "fuzz_plist: keys without values, or nesting past the limit\n");
            std::abort();
        }
    } catch (const std::runtime_error&) {
    }
    return 0;
}
