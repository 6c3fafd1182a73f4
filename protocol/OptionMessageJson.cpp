// The messages of the options table (camera, mode, sampling): their keys are
// the table's wire keys (core/scene/RenderOptions.h), read and written here.
#include <charconv>
#include <cmath>
#include <set>

#include <nlohmann/json.hpp>

#include "protocol/ClientMessageJson_p.h"
#include "protocol/JsonFields.h"

namespace lucent::remote {
namespace {

using Json = nlohmann::json;

// The keys a message of options must hold.
std::set<std::string> requiredOptionKeys(std::string_view type) {
    return type == "mode" ? std::set<std::string>{"mode"} : std::set<std::string>{};
}

std::string shortest(double v) {
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
    return std::string(buffer, result.ptr);
}

std::string choicesText(const RenderOption& o) {
    std::string text;
    for (const std::string_view c : o.choices) {
        text += (text.empty() ? "" : ", ") + std::string(c);
    }
    return text;
}

// The JSON value as the table's text: numbers for Number and Integer options,
// strings for Choice, true/false for Switch.
std::string optionText(const Json& value, const RenderOption& o, const std::string& type) {
    const std::string where = type + ": '" + std::string(o.wireKey) + "'";
    switch (o.kind) {
    case OptionKind::Number:
    case OptionKind::Integer:
        if (!value.is_number() || !std::isfinite(value.get<double>())) {
            throwBadRequest(where + " must be a finite number");
        }
        return value.is_number_integer() ? std::to_string(value.get<long long>())
                                         : shortest(value.get<double>());
    case OptionKind::Choice:
        if (!value.is_string()) {
            throwBadRequest(where + " must be one of " + choicesText(o) + " (a string)");
        }
        return value.get<std::string>();
    case OptionKind::Switch:
        if (!value.is_boolean()) {
            throwBadRequest(where + " must be true or false");
        }
        return value.get<bool>() ? "true" : "false";
    case OptionKind::Size:
    case OptionKind::Box:
    case OptionKind::Window:
        break;
    }
    throw std::logic_error("the image size and clip box travel in their own messages, not " + type);
}

Json optionJson(const OptionValue& v) {
    const std::string& t = v.text;
    switch (v.option->kind) {
    case OptionKind::Number: {
        double d = 0.0;
        std::from_chars(t.data(), t.data() + t.size(), d);
        return d;
    }
    case OptionKind::Integer: {
        long long n = 0;
        std::from_chars(t.data(), t.data() + t.size(), n);
        return n;
    }
    case OptionKind::Choice:
        return t;
    case OptionKind::Switch:
        return t == "true";
    case OptionKind::Size:
    case OptionKind::Box:
    case OptionKind::Window:
        break;
    }
    throw std::logic_error("the image size and clip box travel in their own messages");
}

} // namespace

OptionUpdate parseOptions(const Json& m, const std::string& type) {
    const std::vector<const RenderOption*> rows = wireOptions(type);
    std::set<std::string> known;
    for (const RenderOption* o : rows) {
        known.insert(std::string(o->wireKey));
    }
    checkKeys(m, type, known);
    for (const std::string& key : requiredOptionKeys(type)) {
        if (!m.contains(key)) {
            throwBadRequest(type + ": '" + key + "' is missing");
        }
    }
    OptionUpdate update;
    for (const RenderOption* o : rows) {
        const auto it = m.find(std::string(o->wireKey));
        if (it != m.end()) {
            update.values.push_back(checkedOptionValue(type, *o, optionText(*it, *o, type)));
        }
    }
    return update;
}

void writeOptions(Json& m, const OptionUpdate& update) {
    for (const OptionValue& v : update.values) {
        m[std::string(v.option->wireKey)] = optionJson(v);
    }
}

} // namespace lucent::remote
