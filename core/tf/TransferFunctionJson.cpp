// The transfer-function JSON format (see TransferFunction.h): parsing with field-
// level errors, and a writer whose numbers read back exactly.
#include "core/tf/TransferFunction.h"

#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

namespace lucent {

namespace {

using nlohmann::json;

class Parser {
public:
    explicit Parser(const std::string& source) : source_(source) {}

    [[noreturn]] void fail(const std::string& field, const std::string& message) const {
        throw TransferFunctionError(source_ + ": field '" + field + "': " + message);
    }

    template <std::size_t N>
    void checkKeys(const json& object, const std::string& prefix,
                   const std::array<const char*, N>& known) const {
        for (const auto& item : object.items()) {
            const std::string& key = item.key();
            bool found = false;
            std::string list;
            for (const char* k : known) {
                found = found || key == k;
                list += (list.empty() ? "" : ", ") + std::string(k);
            }
            if (!found) {
                std::string hint = key == "color" ? " (did you mean 'colour'?)" : "";
                fail(prefix + key, "unknown key" + hint + "; the known keys are " + list);
            }
        }
    }

    std::string string(const json& object, const char* key) const {
        const auto it = object.find(key);
        if (it == object.end()) {
            return {};
        }
        if (!it->is_string()) {
            fail(key, std::string("expected a string, got ") + it->type_name());
        }
        return it->get<std::string>();
    }

    double number(const json& value, const std::string& field) const {
        if (!value.is_number()) {
            fail(field, std::string("expected a number, got ") + value.type_name());
        }
        return value.get<double>();
    }

    // The points of "opacity" (width 2) or "colour" (width 4).
    std::vector<std::vector<double>> points(const json& object, const char* key, std::size_t width,
                                            const char* form) const {
        const auto it = object.find(key);
        if (it == object.end()) {
            fail(key, "missing (a list of " + std::string(form) + ")");
        }
        if (!it->is_array()) {
            fail(key, std::string("expected a list of ") + form + ", got " + it->type_name());
        }
        std::vector<std::vector<double>> result;
        for (std::size_t n = 0; n < it->size(); ++n) {
            const json& point = (*it)[n];
            const std::string field = std::string(key) + "[" + std::to_string(n) + "]";
            if (!point.is_array() || point.size() != width) {
                fail(field, std::string("expected ") + form);
            }
            std::vector<double> numbers;
            for (std::size_t k = 0; k < width; ++k) {
                numbers.push_back(number(point[k], field));
            }
            result.push_back(std::move(numbers));
        }
        return result;
    }

    Shading shading(const json& object) const {
        Shading result;
        const auto it = object.find("shading");
        if (it == object.end()) {
            return result;
        }
        if (!it->is_object()) {
            fail("shading", std::string("expected an object, got ") + it->type_name());
        }
        checkKeys(*it, "shading.",
                  std::array{"enabled", "ambient", "diffuse", "specular", "specular_power"});
        if (const auto e = it->find("enabled"); e != it->end()) {
            if (!e->is_boolean()) {
                fail("shading.enabled",
                     std::string("expected true or false, got ") + e->type_name());
            }
            result.enabled = e->get<bool>();
        }
        const auto term = [&](const char* key, double& out) {
            if (const auto t = it->find(key); t != it->end()) {
                out = number(*t, std::string("shading.") + key);
            }
        };
        term("ambient", result.ambient);
        term("diffuse", result.diffuse);
        term("specular", result.specular);
        term("specular_power", result.specularPower);
        return result;
    }

private:
    const std::string& source_;
};

std::string formatNumber(double v) {
    if (!std::isfinite(v)) {
        return "null"; // JSON has no NaN or infinity; reading it back is an error
    }
    std::array<char, 64> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
    return std::string(buffer.data(), result.ptr);
}

} // namespace

TransferFunction parseTransferFunction(std::string_view text, const std::string& sourceName) {
    json root;
    try {
        root = json::parse(text.begin(), text.end());
    } catch (const json::exception& e) {
        std::string what = e.what();
        if (const auto close = what.find("] "); what.starts_with("[json") && close != what.npos) {
            what = what.substr(close + 2);
        }
        throw TransferFunctionError(sourceName + ": malformed JSON: " + what);
    }
    const Parser parser(sourceName);
    if (!root.is_object()) {
        throw TransferFunctionError(sourceName + ": expected a JSON object at the top level, got " +
                                    root.type_name());
    }
    parser.checkKeys(root, "", std::array{"name", "modality", "opacity", "colour", "shading"});
    TransferFunction tf;
    tf.name = parser.string(root, "name");
    tf.modality = parser.string(root, "modality");
    for (const auto& p : parser.points(root, "opacity", 2, "[value, opacity] pairs")) {
        tf.opacity.push_back({p[0], p[1]});
    }
    for (const auto& p : parser.points(root, "colour", 4, "[value, r, g, b] quadruples")) {
        tf.colour.push_back({p[0], {p[1], p[2], p[3]}});
    }
    tf.shading = parser.shading(root);
    try {
        tf.validate();
    } catch (const std::invalid_argument& e) {
        throw TransferFunctionError(sourceName + ": " + e.what());
    }
    return tf;
}

TransferFunction readTransferFunction(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw TransferFunctionError(path.string() + ": cannot open: " + std::strerror(errno));
    }
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) {
        throw TransferFunctionError(path.string() + ": read error");
    }
    return parseTransferFunction(text.str(), path.string());
}

std::string toJson(const TransferFunction& tf) {
    std::string out = "{\n";
    out += "  \"name\": " + json(tf.name).dump() + ",\n";
    out += "  \"modality\": " + json(tf.modality).dump() + ",\n";
    out += "  \"opacity\": [";
    for (std::size_t n = 0; n < tf.opacity.size(); ++n) {
        const OpacityPoint& p = tf.opacity[n];
        out += (n ? ",\n    [" : "\n    [") + formatNumber(p.value) + ", " +
               formatNumber(p.opacity) + "]";
    }
    out += "\n  ],\n  \"colour\": [";
    for (std::size_t n = 0; n < tf.colour.size(); ++n) {
        const ColourPoint& p = tf.colour[n];
        out += (n ? ",\n    [" : "\n    [") + formatNumber(p.value) + ", " + formatNumber(p.rgb.r) +
               ", " + formatNumber(p.rgb.g) + ", " + formatNumber(p.rgb.b) + "]";
    }
    const Shading& s = tf.shading;
    out += "\n  ],\n  \"shading\": {\"enabled\": " + std::string(s.enabled ? "true" : "false") +
           ", \"ambient\": " + formatNumber(s.ambient) +
           ", \"diffuse\": " + formatNumber(s.diffuse) +
           ", \"specular\": " + formatNumber(s.specular) +
           ", \"specular_power\": " + formatNumber(s.specularPower) + "}\n}\n";
    return out;
}

void writeTransferFunction(const TransferFunction& tf, const std::filesystem::path& path) {
    tf.validate();
    const std::string text = toJson(tf);
    std::filesystem::path temporary = path;
    temporary += ".tmp";
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) {
            throw TransferFunctionError(path.string() + ": cannot write: " + std::strerror(errno));
        }
        out << text;
        out.flush();
        if (!out) {
            std::error_code ignored;
            std::filesystem::remove(temporary, ignored);
            throw TransferFunctionError(path.string() + ": write error");
        }
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw TransferFunctionError(path.string() + ": cannot replace: " + error.message());
    }
}

} // namespace lucent
