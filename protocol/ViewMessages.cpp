#include "protocol/ViewMessages.h"

#include <algorithm>

namespace lucent::remote {

std::vector<ClientMessage> viewMessages(const RenderDescription& d) {
    ModeUpdate mode{optionUpdate(kWireMode, d)};
    if (d.mode != RenderMode::Isosurface) {
        std::erase_if(mode.values, [](const OptionValue& v) { return v.option->wireKey == "iso"; });
    }
    return {SizeUpdate{std::clamp(d.width, kMinImageSide, kMaxImageSide),
                       std::clamp(d.height, kMinImageSide, kMaxImageSide)},
            TransferFunctionUpdate{std::nullopt, d.transferFunction},
            mode,
            ClipUpdate{d.clip},
            CameraUpdate{optionUpdate(kWireCamera, d)},
            SamplingUpdate{optionUpdate(kWireSampling, d)}};
}

std::optional<std::string> applyViewMessage(const ClientMessage& message, RenderDescription& d) {
    if (const auto* options = std::get_if<CameraUpdate>(&message)) {
        applyOptionUpdate(*options, d);
    } else if (const auto* mode = std::get_if<ModeUpdate>(&message)) {
        applyOptionUpdate(*mode, d);
    } else if (const auto* sampling = std::get_if<SamplingUpdate>(&message)) {
        applyOptionUpdate(*sampling, d);
    } else if (const auto* tf = std::get_if<TransferFunctionUpdate>(&message)) {
        try {
            d.transferFunction = tf->preset ? loadPreset(*tf->preset) : *tf->transferFunction;
        } catch (const TransferFunctionError& e) {
            return std::string(e.what());
        }
    } else if (const auto* clip = std::get_if<ClipUpdate>(&message)) {
        d.clip = clip->box;
    } else if (const auto* size = std::get_if<SizeUpdate>(&message)) {
        d.width = size->width;
        d.height = size->height;
    }
    return std::nullopt;
}

} // namespace lucent::remote
