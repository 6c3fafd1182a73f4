#include "protocol/FrameMessage.h"

#include <nlohmann/json.hpp>

#include "protocol/JsonIntegers.h"
#include "protocol/SliceMessageJson_p.h"

namespace lucent::remote {

using Json = nlohmann::json;

std::string frameMessage(const FrameHeader& header, std::string_view imageBytes) {
    Json json = Json{{"width", header.width},
                     {"height", header.height},
                     {"format", header.format},
                     {"seq", header.seq},
                     {"quality", qualityName(header.quality)},
                     {"render_ms", header.renderMs},
                     {"encode_ms", header.encodeMs},
                     {"scale", header.scale},
                     {"jpeg_quality", header.jpegQuality}};
    if (header.projection) {
        json["projection"] = *header.projection;
    }
    if (header.slice) {
        writeSliceFrameInfo(json, *header.slice);
    }
    const std::string text = json.dump();
    const auto n = static_cast<std::uint32_t>(text.size());
    std::string out;
    out.reserve(4 + text.size() + imageBytes.size());
    for (int shift : {24, 16, 8, 0}) {
        out.push_back(static_cast<char>((n >> shift) & 0xffu));
    }
    out += text;
    out += imageBytes;
    return out;
}

ParsedFrame parseFrameMessage(std::string_view message) {
    auto malformed = [](const std::string& why) {
        return ProtocolError("malformed", "frame: " + why, true);
    };
    if (message.size() < 4) {
        throw malformed("shorter than its length field");
    }
    std::uint32_t n = 0;
    for (int i = 0; i < 4; ++i) {
        n = (n << 8) | static_cast<unsigned char>(message[static_cast<std::size_t>(i)]);
    }
    if (n > message.size() - 4) {
        throw malformed("header length exceeds the message");
    }
    const Json h = Json::parse(message.substr(4, n), nullptr, false);
    if (h.is_discarded() || !h.is_object()) {
        throw malformed("header is not a JSON object");
    }
    ParsedFrame f;
    try {
        f.header.width = jsonInteger<int>(h.at("width"), "frame: header: width");
        f.header.height = jsonInteger<int>(h.at("height"), "frame: header: height");
        f.header.format = h.at("format").get<std::string>();
        f.header.seq = jsonInteger<std::uint64_t>(h.at("seq"), "frame: header: seq");
        f.header.quality = h.at("quality").get<std::string>() == "interactive"
                               ? Quality::Interactive
                               : Quality::Still;
        f.header.renderMs = h.value("render_ms", 0.0);
        f.header.encodeMs = h.value("encode_ms", 0.0);
        f.header.scale = h.value("scale", 1.0);
        f.header.jpegQuality =
            h.contains("jpeg_quality")
                ? jsonInteger<int>(h.at("jpeg_quality"), "frame: header: jpeg_quality")
                : 0;
        if (const auto p = h.find("projection"); p != h.end()) {
            if (!p->is_array() || p->size() != 12) {
                throw malformed("header: 'projection' must hold 12 numbers");
            }
            f.header.projection = p->get<std::array<double, 12>>();
        }
        if (h.contains("view")) {
            f.header.slice = readSliceFrameInfo(h);
        }
    } catch (const Json::exception& e) {
        throw malformed(std::string("header: ") + e.what());
    } catch (const std::invalid_argument& e) {
        throw malformed(std::string("header: ") + e.what());
    }
    f.image = message.substr(4 + n);
    return f;
}

} // namespace lucent::remote
