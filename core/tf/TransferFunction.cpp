#include "core/tf/TransferFunction.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace lucent {

namespace {

// Piecewise-linear evaluation over points sorted by value; constant beyond the ends.
template <typename Point, typename Get>
auto evaluate(const std::vector<Point>& points, double value, Get get) -> decltype(get(points[0])) {
    using Result = decltype(get(points[0]));
    if (points.empty()) {
        return Result(0.0);
    }
    if (!(value > points.front().value)) { // also NaN: the first point
        return get(points.front());
    }
    if (value >= points.back().value) {
        return get(points.back());
    }
    const auto upper = std::upper_bound(points.begin(), points.end(), value,
                                        [](double v, const Point& p) { return v < p.value; });
    const Point& b = *upper;
    const Point& a = *(upper - 1);
    const double t = (value - a.value) / (b.value - a.value);
    return get(a) + (get(b) - get(a)) * t;
}

[[noreturn]] void fail(const std::string& field, const std::string& message) {
    throw std::invalid_argument("field '" + field + "': " + message);
}

std::string number(double v) {
    std::ostringstream out;
    out.precision(10);
    out << v;
    return out.str();
}

void checkUnit(const std::string& field, const char* what, double v) {
    if (!std::isfinite(v)) {
        fail(field, std::string(what) + " is not a finite number");
    }
    if (v < 0.0 || v > 1.0) {
        fail(field, std::string(what) + " " + number(v) + " is outside [0, 1]");
    }
}

template <typename Point>
void checkValues(const std::vector<Point>& points, const std::string& list) {
    if (points.empty()) {
        fail(list, "the list is empty (at least one point is needed)");
    }
    for (std::size_t n = 0; n < points.size(); ++n) {
        const std::string field = list + "[" + std::to_string(n) + "]";
        if (!std::isfinite(points[n].value)) {
            fail(field, "value is not a finite number");
        }
        if (n > 0 && !(points[n].value > points[n - 1].value)) {
            fail(field, "values must be strictly increasing, but " + number(points[n].value) +
                            (points[n].value == points[n - 1].value ? " repeats " : " follows ") +
                            number(points[n - 1].value));
        }
    }
}

void checkShadingTerm(const char* key, double v) {
    const std::string field = std::string("shading.") + key;
    if (!std::isfinite(v)) {
        fail(field, "is not a finite number");
    }
    if (v < 0.0) {
        fail(field, number(v) + " is negative");
    }
}

} // namespace

double TransferFunction::opacityAt(double value) const {
    return evaluate(opacity, value, [](const OpacityPoint& p) { return p.opacity; });
}

glm::dvec3 TransferFunction::colourAt(double value) const {
    return evaluate(colour, value, [](const ColourPoint& p) { return p.rgb; });
}

double TransferFunction::maxOpacity(double lo, double hi) const {
    if (lo > hi) {
        std::swap(lo, hi);
    }
    double result = std::max(opacityAt(lo), opacityAt(hi));
    for (const OpacityPoint& p : opacity) {
        if (p.value > lo && p.value < hi) {
            result = std::max(result, p.opacity);
        }
    }
    return result;
}

void TransferFunction::validate() const {
    if (modality != "" && modality != "CT" && modality != "MR") {
        fail("modality", "'" + modality + "' is not one of \"CT\", \"MR\" or \"\"");
    }
    checkValues(opacity, "opacity");
    for (std::size_t n = 0; n < opacity.size(); ++n) {
        checkUnit("opacity[" + std::to_string(n) + "]", "opacity", opacity[n].opacity);
    }
    checkValues(colour, "colour");
    for (std::size_t n = 0; n < colour.size(); ++n) {
        const std::string field = "colour[" + std::to_string(n) + "]";
        checkUnit(field, "red", colour[n].rgb.r);
        checkUnit(field, "green", colour[n].rgb.g);
        checkUnit(field, "blue", colour[n].rgb.b);
    }
    checkShadingTerm("ambient", shading.ambient);
    checkShadingTerm("diffuse", shading.diffuse);
    checkShadingTerm("specular", shading.specular);
    checkShadingTerm("specular_power", shading.specularPower);
}

} // namespace lucent
