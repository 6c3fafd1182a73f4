#include "core/report/MeasurementGeometryText.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace lucent {

namespace {

constexpr const char* kMagic = "lucent-geometry-1";

std::string number(double v) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.17g", v);
    return buffer;
}

// strtod reads "nan" and "inf", which an istream does not.
bool parseNumber(const std::string& token, double& out) {
    char* end = nullptr;
    out = std::strtod(token.c_str(), &end);
    return !token.empty() && end == token.c_str() + token.size();
}

} // namespace

std::string encodeMeasurementGeometry(const Measurement& m) {
    std::string out = std::string(kMagic) + " kind " + std::to_string(static_cast<int>(m.kind)) +
                      " id " + std::to_string(m.id) + " labelled " + (m.label.empty() ? "0" : "1") +
                      " points " + std::to_string(m.points.size());
    for (const glm::dvec3& p : m.points) {
        out += " " + number(p.x) + " " + number(p.y) + " " + number(p.z);
    }
    const SlicePlane& s = m.plane;
    out += " plane";
    for (const glm::dvec3* v : {&s.centre, &s.u, &s.v}) {
        out += " " + number(v->x) + " " + number(v->y) + " " + number(v->z);
    }
    out += " " + number(s.pixelSize) + " " + std::to_string(s.width) + " " +
           std::to_string(s.height) + " " + number(s.slabThickness) + " " +
           std::to_string(static_cast<int>(s.slabMode));
    const RoiStatistics& r = m.statistics;
    out += " roi " + number(r.mean) + " " + number(r.standardDeviation) + " " + number(r.minimum) +
           " " + number(r.maximum) + " " + number(r.areaMm2) + " " + std::to_string(r.samples);
    out += " unit " + (m.unit.empty() ? std::string("-") : m.unit);
    if (m.suv) {
        out += " suv " + number(m.suv->max) + " " + number(m.suv->mean) + " " +
               number(m.suv->peak) + " " + std::to_string(m.suv->voxels);
    }
    return out;
}

std::optional<DecodedGeometry> decodeMeasurementGeometry(const std::string& text) {
    std::istringstream in(text);
    std::vector<std::string> t;
    for (std::string token; in >> token;) {
        t.push_back(token);
    }
    std::size_t i = 0;
    auto word = [&](const char* expected) { return i < t.size() && t[i++] == expected; };
    auto num = [&](double& v) { return i < t.size() && parseNumber(t[i++], v); };
    auto integer = [&](long long& v) {
        double d = 0.0;
        if (!num(d) || d != static_cast<double>(static_cast<long long>(d))) {
            return false;
        }
        v = static_cast<long long>(d);
        return true;
    };
    auto vec = [&](glm::dvec3& v) { return num(v.x) && num(v.y) && num(v.z); };

    DecodedGeometry g;
    Measurement& m = g.measurement;
    long long kind = 0, id = 0, labelled = 0, count = 0;
    if (!word(kMagic) || !word("kind") || !integer(kind) || kind < 0 ||
        kind > static_cast<int>(MeasurementKind::Ellipse) || !word("id") || !integer(id) ||
        id < 0 || !word("labelled") || !integer(labelled) || !word("points") || !integer(count) ||
        count < 0 || count > 64) {
        return std::nullopt;
    }
    m.kind = static_cast<MeasurementKind>(kind);
    m.id = static_cast<std::uint64_t>(id);
    g.labelled = labelled != 0;
    m.points.resize(static_cast<std::size_t>(count));
    for (glm::dvec3& p : m.points) {
        if (!vec(p)) {
            return std::nullopt;
        }
    }
    SlicePlane& s = m.plane;
    long long width = 0, height = 0, mode = 0, samples = 0;
    if (!word("plane") || !vec(s.centre) || !vec(s.u) || !vec(s.v) || !num(s.pixelSize) ||
        !integer(width) || !integer(height) || !num(s.slabThickness) || !integer(mode) ||
        mode < 0 || mode > static_cast<int>(SlabMode::Average)) {
        return std::nullopt;
    }
    s.width = static_cast<int>(width);
    s.height = static_cast<int>(height);
    s.slabMode = static_cast<SlabMode>(mode);
    RoiStatistics& r = m.statistics;
    if (!word("roi") || !num(r.mean) || !num(r.standardDeviation) || !num(r.minimum) ||
        !num(r.maximum) || !num(r.areaMm2) || !integer(samples) || samples < 0 || !word("unit") ||
        i >= t.size()) {
        return std::nullopt;
    }
    r.samples = static_cast<std::size_t>(samples);
    m.unit = t[i] == "-" ? std::string() : t[i];
    ++i;
    if (i < t.size()) { // SUVs, written since PET in SUV; older texts end at the unit
        SuvStatistics suv;
        long long voxels = 0;
        if (!word("suv") || !num(suv.max) || !num(suv.mean) || !num(suv.peak) || !integer(voxels) ||
            voxels < 0) {
            return std::nullopt;
        }
        suv.voxels = static_cast<std::size_t>(voxels);
        m.suv = suv;
    }
    return g;
}

} // namespace lucent
