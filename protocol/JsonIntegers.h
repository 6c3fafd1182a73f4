#pragma once
// Integer fields of the protocol's JSON, read strictly: nlohmann's get<int>()
// converts a float such as 2.2e15 by a cast whose result is undefined when it
// is out of range (fuzz_protocol found one in a frame header), and wraps
// integers silently. Private to protocol/ (.cpp files only).

#include <limits>
#include <string>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "protocol/ProtocolError.h"

namespace lucent::remote {

// `value` as a T when it is a JSON integer within T's range; else a fatal
// "malformed" ProtocolError naming `field`.
template <class T> T jsonInteger(const nlohmann::json& value, const std::string& field) {
    static_assert(std::is_integral_v<T>);
    bool fits = false;
    if (value.is_number_unsigned()) {
        fits =
            value.get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<T>::max());
    } else if (value.is_number_integer()) {
        const auto v = value.get<std::int64_t>();
        fits = std::is_signed_v<T>
                   ? v >= static_cast<std::int64_t>(std::numeric_limits<T>::min()) &&
                         v <= static_cast<std::int64_t>(std::numeric_limits<T>::max())
                   : v >= 0;
    }
    if (!fits) {
        throw ProtocolError("malformed",
                            "'" + field + "' must be an integer from " +
                                std::to_string(std::numeric_limits<T>::min()) + " to " +
                                std::to_string(std::numeric_limits<T>::max()) + ", not " +
                                value.dump().substr(0, 40),
                            true);
    }
    return value.get<T>();
}

} // namespace lucent::remote
