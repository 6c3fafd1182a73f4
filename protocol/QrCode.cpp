#include "protocol/QrCode.h"

#include <memory>
#include <stdexcept>
#include <string>

#include <qrencode.h>

namespace lucent::remote {
namespace {

struct QrFree {
    void operator()(QRcode* code) const { QRcode_free(code); }
};

} // namespace

QrCode encodeQrCode(std::string_view text) {
    const std::string bytes(text);
    const std::unique_ptr<QRcode, QrFree> code(QRcode_encodeData(
        int(bytes.size()), reinterpret_cast<const unsigned char*>(bytes.data()), 0, QR_ECLEVEL_M));
    if (!code) {
        throw std::runtime_error("a QR code cannot hold " + std::to_string(bytes.size()) +
                                 " bytes of text");
    }
    QrCode qr;
    qr.size = code->width;
    qr.modules.resize(std::size_t(code->width) * std::size_t(code->width));
    for (std::size_t n = 0; n < qr.modules.size(); ++n) {
        qr.modules[n] = code->data[n] & 1; // bit 0: dark; the others say what the module is
    }
    return qr;
}

} // namespace lucent::remote
