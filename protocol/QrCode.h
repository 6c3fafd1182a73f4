#pragma once
// A QR code as a module matrix, made by libqrencode: the one place where Lucent
// makes QR codes (the server's invite links; clients draw the matrix they are
// sent, adding the quiet zone of 4 light modules around it).

#include <cstdint>
#include <string_view>
#include <vector>

namespace lucent::remote {

struct QrCode {
    int size = 0;                      // modules a side, without the quiet zone
    std::vector<std::uint8_t> modules; // size * size, row by row, 1 dark, 0 light
    bool dark(int x, int y) const { return modules[std::size_t(y) * std::size_t(size) + x] != 0; }
    bool operator==(const QrCode&) const = default;
};

// The light modules a reader needs around the code.
inline constexpr int kQrQuietZone = 4;

// `text` (8-bit mode, error correction level M, the smallest version that holds
// it). Throws std::runtime_error when it cannot be encoded (too long).
QrCode encodeQrCode(std::string_view text);

} // namespace lucent::remote
