// fuzz_tf_json: one input is a transfer-function JSON file (core/tf). It is
// parsed and validated or refused with a TransferFunctionError; an accepted
// function is written (toJson) and read back to itself (the writer promises an
// exact round trip), and is evaluated as the ray casters evaluate it.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "core/tf/TransferFunction.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace lucent;
    const std::string_view json(reinterpret_cast<const char*>(data), size);
    TransferFunction tf;
    try {
        tf = parseTransferFunction(json, "fuzz input");
    } catch (const TransferFunctionError&) {
        return 0;
    }
    const std::string written = toJson(tf);
    if (!(parseTransferFunction(written, "written fuzz input") == tf)) {
        std::fprintf(stderr, "fuzz_tf_json: toJson does not read back as itself:\n%s\n",
                     written.c_str());
        std::abort();
    }
    const double lo = tf.opacity.front().value;
    const double hi = tf.opacity.back().value;
    (void)tf.opacityAt(lo - 1.0);
    (void)tf.opacityAt(0.5 * (lo + hi));
    (void)tf.colourAt(tf.colour.front().value + 0.5);
    (void)tf.maxOpacity(hi, lo);
    return 0;
}
