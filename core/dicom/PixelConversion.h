#pragma once
// Stored values -> rescaled voxels: mask to BitsStored, sign-extend, apply
// slope and intercept. Private to lucent_io.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "core/dicom/FrameDecoder.h"

namespace lucent {

template <class Raw, class Out, bool Masked, bool Integral>
void convertLoop(const char* src, std::size_t n, const RawFormat& fmt, double slope,
                 double intercept, Out* dst) {
    using Wide = std::conditional_t<(sizeof(Raw) < 4), std::int32_t, std::int64_t>;
    using URaw = std::make_unsigned_t<Raw>;
    const int shift = fmt.highBit + 1 - fmt.bitsStored;
    const Wide mask = static_cast<Wide>((std::int64_t{1} << fmt.bitsStored) - 1);
    const Wide signBit = static_cast<Wide>(std::int64_t{1} << (fmt.bitsStored - 1));
    const bool isSigned = fmt.isSigned;
    const Wide islope = static_cast<Wide>(slope);
    const Wide iintercept = static_cast<Wide>(intercept);
    for (std::size_t x = 0; x < n; ++x) {
        Raw raw;
        std::memcpy(&raw, src + x * sizeof(Raw), sizeof(Raw));
        Wide v = static_cast<Wide>(raw);
        if constexpr (Masked) {
            v = (static_cast<Wide>(static_cast<URaw>(raw)) >> shift) & mask;
            if (isSigned) {
                v -= (v & signBit) ? mask + 1 : 0;
            }
        }
        if constexpr (Integral) {
            dst[x] = static_cast<Out>(v * islope + iintercept);
        } else if constexpr (std::is_integral_v<Out>) {
            dst[x] = static_cast<Out>(std::lround(static_cast<double>(v) * slope + intercept));
        } else {
            dst[x] = static_cast<Out>(static_cast<double>(v) * slope + intercept);
        }
    }
}

template <class Raw, class Out>
void convertTyped(const char* src, std::size_t n, const RawFormat& fmt, double slope,
                  double intercept, Out* dst) {
    const bool masked = fmt.bitsStored < fmt.bitsAllocated;
    const bool integral =
        std::is_integral_v<Out> && slope == std::round(slope) && intercept == std::round(intercept);
    if (masked) {
        return integral ? convertLoop<Raw, Out, true, true>(src, n, fmt, slope, intercept, dst)
                        : convertLoop<Raw, Out, true, false>(src, n, fmt, slope, intercept, dst);
    }
    return integral ? convertLoop<Raw, Out, false, true>(src, n, fmt, slope, intercept, dst)
                    : convertLoop<Raw, Out, false, false>(src, n, fmt, slope, intercept, dst);
}

// Converts one frame of n stored values into dst (int16_t, uint16_t or float).
template <class Out>
void convertFrame(const char* src, std::size_t n, const RawFormat& fmt, double slope,
                  double intercept, Out* dst) {
    switch (fmt.bitsAllocated) {
    case 8:
        return fmt.isSigned ? convertTyped<std::int8_t>(src, n, fmt, slope, intercept, dst)
                            : convertTyped<std::uint8_t>(src, n, fmt, slope, intercept, dst);
    case 16:
        return fmt.isSigned ? convertTyped<std::int16_t>(src, n, fmt, slope, intercept, dst)
                            : convertTyped<std::uint16_t>(src, n, fmt, slope, intercept, dst);
    default:
        return fmt.isSigned ? convertTyped<std::int32_t>(src, n, fmt, slope, intercept, dst)
                            : convertTyped<std::uint32_t>(src, n, fmt, slope, intercept, dst);
    }
}

} // namespace lucent
