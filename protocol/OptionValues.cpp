#include "protocol/OptionValues.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "protocol/ProtocolError.h"

namespace lucent::remote {
namespace {

constexpr WireBound kWireBounds[] = {
    {"camera", "zoom", 0.01, 100.0, true, "must lie between 0.01 and 100"},
    {"camera", "distance", 0.0, kMaxCameraDistance, false,
     "must lie between 0 (fit the volume) and 100000 mm"},
    {"camera", "pan_right", -kMaxCameraPan, kMaxCameraPan, false,
     "must lie between -100000 and 100000 mm"},
    {"camera", "pan_up", -kMaxCameraPan, kMaxCameraPan, false,
     "must lie between -100000 and 100000 mm"},
    {"sampling", "step", kMinWireStep, std::numeric_limits<double>::max(), false,
     "must be at least 0.05 voxels"},
};

std::string where(std::string_view message, std::string_view key) {
    return std::string(message) + ": '" + std::string(key) + "'";
}

void checkWireBound(std::string_view message, const RenderOption& option, std::string_view text) {
    for (const WireBound& b : kWireBounds) {
        if (b.message != message || b.key != option.wireKey) {
            continue;
        }
        double v = 0.0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || end != text.data() + text.size()) {
            return; // not a number: the table says so
        }
        const bool inside = b.exclusive ? v > b.min && v < b.max : v >= b.min && v <= b.max;
        if (!inside) {
            throwBadRequest(where(message, option.wireKey) + " " + std::string(b.words));
        }
    }
}

} // namespace

std::optional<std::string> OptionUpdate::text(std::string_view wireKey) const {
    for (const OptionValue& v : values) {
        if (v.option->wireKey == wireKey) {
            return v.text;
        }
    }
    return std::nullopt;
}

std::optional<double> OptionUpdate::number(std::string_view wireKey) const {
    const auto t = text(wireKey);
    if (!t) {
        return std::nullopt;
    }
    double v = 0.0;
    std::from_chars(t->data(), t->data() + t->size(), v);
    return v;
}

std::span<const WireBound> wireBounds() {
    return kWireBounds;
}

std::vector<const RenderOption*> wireOptions(std::string_view message) {
    std::vector<const RenderOption*> rows;
    for (const RenderOption& o : renderOptions()) {
        if (o.wireMessage == message) {
            rows.push_back(&o);
        }
    }
    return rows;
}

const RenderOption* findWireOption(std::string_view message, std::string_view key) {
    for (const RenderOption& o : renderOptions()) {
        if (o.wireMessage == message && o.wireKey == key) {
            return &o;
        }
    }
    return nullptr;
}

OptionValue checkedOptionValue(std::string_view message, const RenderOption& option,
                               std::string_view text) {
    checkWireBound(message, option, text);
    RenderDescription scratch;
    try {
        applyRenderOption(scratch, option, text);
    } catch (const std::invalid_argument& e) {
        // The table's reason, without its own "name: " in front.
        std::string reason = e.what();
        const std::string named = std::string(option.name) + ": ";
        if (reason.starts_with(named)) {
            reason.erase(0, named.size());
        }
        throwBadRequest(where(message, option.wireKey) + ": " + reason);
    }
    return {&option, renderOptionValue(scratch, option)};
}

OptionUpdate optionUpdate(std::string_view message, const RenderDescription& description) {
    OptionUpdate update;
    for (const RenderOption* o : wireOptions(message)) {
        update.values.push_back({o, renderOptionValue(description, *o)});
    }
    return update;
}

void applyOptionUpdate(const OptionUpdate& update, RenderDescription& description) {
    for (const OptionValue& v : update.values) {
        applyRenderOption(description, *v.option, v.text);
    }
}

} // namespace lucent::remote
