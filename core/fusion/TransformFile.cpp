#include "core/fusion/TransformFile.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

namespace lucent {
namespace {

using Json = nlohmann::ordered_json;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw TransformFileError(path + ": " + what);
}

} // namespace

glm::dmat4 readTransformFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        fail(path, "cannot read the transform file");
    }
    std::stringstream text;
    text << in.rdbuf();
    Json root;
    try {
        root = Json::parse(text.str());
    } catch (const Json::parse_error& e) {
        fail(path, std::string("not JSON (") + e.what() + ")");
    }
    if (!root.is_object() || !root.contains("matrix")) {
        fail(path, "no \"matrix\" (4 rows of 4 numbers, fixed LPS mm -> moving LPS mm)");
    }
    const Json& rows = root["matrix"];
    if (!rows.is_array() || rows.size() != 4) {
        fail(path, "\"matrix\" is not 4 rows of 4 numbers");
    }
    glm::dmat4 m(1.0);
    for (int r = 0; r < 4; ++r) {
        const Json& row = rows[std::size_t(r)];
        if (!row.is_array() || row.size() != 4) {
            fail(path, "\"matrix\" row " + std::to_string(r) + " is not 4 numbers");
        }
        for (int c = 0; c < 4; ++c) {
            const Json& v = row[std::size_t(c)];
            if (!v.is_number() || !std::isfinite(v.get<double>())) {
                fail(path, "\"matrix\"[" + std::to_string(r) + "][" + std::to_string(c) +
                               "] is not a finite number");
            }
            m[c][r] = v.get<double>(); // GLM is column-major: m[column][row]
        }
    }
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0) {
        fail(path, "\"matrix\" row 3 is not 0 0 0 1 (an affine transform is needed)");
    }
    // Singular: the linear part's determinant against the scale of its entries.
    const glm::dmat3 linear(m);
    double scale = 0.0;
    for (int c = 0; c < 3; ++c) {
        scale = std::max(scale, glm::length(linear[c]));
    }
    if (!(std::abs(glm::determinant(linear)) > 1e-9 * scale * scale * scale)) {
        fail(path, "\"matrix\" is singular (its 3x3 part cannot be inverted)");
    }
    return m;
}

void writeTransformFile(const std::string& path, const glm::dmat4& fixedToMoving,
                        const std::optional<TransformFileFacts>& facts) {
    Json rows = Json::array();
    for (int r = 0; r < 4; ++r) {
        Json row = Json::array();
        for (int c = 0; c < 4; ++c) {
            row.push_back(fixedToMoving[c][r]);
        }
        rows.push_back(row);
    }
    Json root = {{"matrix", rows}, {"convention", "fixed LPS mm -> moving LPS mm, row-major rows"}};
    if (facts) {
        root["metric_name"] = facts->metricName;
        root["metric"] = facts->metric;
        root["iterations"] = facts->iterations;
        root["seconds"] = facts->seconds;
        root["converged"] = facts->converged;
        root["reason"] = facts->reason;
        if (!facts->transform.empty()) {
            root["transform"] = facts->transform;
        }
        if (!facts->initialisation.empty()) {
            root["initialisation"] = facts->initialisation;
        }
    }
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << root.dump(4) << "\n";
    if (!out.flush()) {
        fail(path, "cannot write the transform file");
    }
}

} // namespace lucent
