// Pre-integrated classification (Engel, Kraus, Ertl 2001): the colour and opacity
// of a ray segment whose data value goes linearly from sf (front) to sb (back).
// The method and its accuracy are described at preintegrateSegment() in the header.
#include "core/tf/SegmentPreintegrator.h"
#include "core/tf/TransferFunction.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/tf/TableRange.h"

namespace lucent {

namespace {

constexpr double kSubstepDepth = 0.25; // optical depth per sub-step
constexpr int kMinSubsteps = 2;        // per piece
constexpr int kMaxSubsteps = 64;       // per piece
constexpr double kOpaqueDepth = 40.0;  // exp(-40) ~ 4e-18: nothing behind is visible

// The mean of tau = -ln(b) over a sub-interval on which the transparency b = 1 - a
// goes linearly from b0 to b1 (closed form; +inf when b is 0 throughout).
double meanExtinction(double b0, double b1) {
    b0 = std::max(b0, 0.0);
    b1 = std::max(b1, 0.0);
    const double mid = 0.5 * (b0 + b1);
    if (mid <= 0.0) {
        return std::numeric_limits<double>::infinity();
    }
    const double half = 0.5 * std::abs(b1 - b0);
    if (half <= 1e-3 * mid) {
        // Series about the midpoint; the next term, (half/mid)^4 / 20, is below 1e-13.
        const double r = half / mid;
        return -std::log(mid) + r * r / 6.0;
    }
    // The antiderivative of ln(b) is b ln(b) - b, which is 0 at b = 0.
    const auto f = [](double b) { return b > 0.0 ? b * std::log(b) - b : 0.0; };
    return -(f(b1) - f(b0)) / (b1 - b0);
}

// Where, as a fraction of a sub-step, its emission is centred. The emission density
// is tau(t) exp(-T(t)) = dq/dt with q(t) = 1 - exp(-T(t)) the opacity accumulated
// from the sub-step's front, so the centroid is 1 - mean(q) / q(1); Simpson's rule
// for mean(q) gives 5/6 - (2/3) q(1/2) / q(1). Exact for a linear or quadratic q (a
// thin sub-step with constant or linearly growing extinction); a linear colour
// integrates exactly at the centroid. q(1/2) and q(1) come from the closed-form depth.
double emissionCentroid(double halfDepth, double depth) {
    const double q = -std::expm1(-depth);
    if (!(q > 0.0)) {
        return 0.5; // nothing is emitted
    }
    const double f = 5.0 / 6.0 - (2.0 / 3.0) * (-std::expm1(-halfDepth) / q);
    return std::clamp(f, 0.0, 1.0);
}

// Integrates segments against one transfer function; the merged breakpoints of its
// opacity and colour are computed once.
class SegmentIntegrator {
public:
    explicit SegmentIntegrator(const TransferFunction& tf) : tf_(tf) {
        for (const OpacityPoint& p : tf.opacity) {
            breakpoints_.push_back(p.value);
        }
        for (const ColourPoint& p : tf.colour) {
            breakpoints_.push_back(p.value);
        }
        std::sort(breakpoints_.begin(), breakpoints_.end());
        breakpoints_.erase(std::unique(breakpoints_.begin(), breakpoints_.end()),
                           breakpoints_.end());
    }

    glm::dvec4 operator()(double sf, double sb, double stepRatio) const {
        if (sf == sb) {
            // The closed form of the ordinary corrected sample.
            const double alpha = 1.0 - std::pow(1.0 - tf_.opacityAt(sf), stepRatio);
            return {tf_.colourAt(sf) * alpha, alpha};
        }
        // The values where a(s) or colour(s) has a kink, in the order the ray meets them.
        std::vector<double> values{sf};
        const auto first =
            std::upper_bound(breakpoints_.begin(), breakpoints_.end(), std::min(sf, sb));
        const auto last =
            std::lower_bound(breakpoints_.begin(), breakpoints_.end(), std::max(sf, sb));
        if (sf < sb) {
            values.insert(values.end(), first, last);
        } else {
            values.insert(values.end(), std::make_reverse_iterator(last),
                          std::make_reverse_iterator(first));
        }
        values.push_back(sb);

        Accumulator acc;
        for (std::size_t n = 0; n + 1 < values.size() && !acc.done(); ++n) {
            const double u0 = (values[n] - sf) / (sb - sf);
            const double u1 = n + 2 == values.size() ? 1.0 : (values[n + 1] - sf) / (sb - sf);
            piece(acc, (u1 - u0) * stepRatio, values[n], values[n + 1]);
        }
        const double alpha = acc.opaque ? 1.0 : -std::expm1(-acc.depth);
        return {acc.rgb, alpha};
    }

private:
    struct Accumulator {
        double depth = 0.0; // optical depth in front of the current position
        bool opaque = false;
        glm::dvec3 rgb{0.0};
        bool done() const { return opaque || depth > kOpaqueDepth; }
    };

    // One piece on which a and colour are linear, `length` dt_ref long, from value
    // v0 to v1.
    void piece(Accumulator& acc, double length, double v0, double v1) const {
        const double b0 = 1.0 - tf_.opacityAt(v0);
        const double b1 = 1.0 - tf_.opacityAt(v1);
        const glm::dvec3 c0 = tf_.colourAt(v0);
        const glm::dvec3 c1 = tf_.colourAt(v1);
        const double depth = length * meanExtinction(b0, b1);
        if (std::isinf(depth)) { // opaque throughout: all that is left is emitted at its front
            acc.rgb += std::exp(-acc.depth) * c0;
            acc.opaque = true;
            return;
        }
        const int count =
            std::clamp(static_cast<int>(std::ceil(std::min(depth, kOpaqueDepth) / kSubstepDepth)),
                       kMinSubsteps, kMaxSubsteps);
        for (int k = 0; k < count && !acc.done(); ++k) {
            const double t0 = static_cast<double>(k) / count;
            const double t1 = static_cast<double>(k + 1) / count;
            const double bs0 = b0 + (b1 - b0) * t0;
            const double bs1 = b0 + (b1 - b0) * t1;
            const double x = length / count * meanExtinction(bs0, bs1);
            if (std::isinf(x)) {
                acc.rgb += std::exp(-acc.depth) * (c0 + (c1 - c0) * t0);
                acc.opaque = true;
                return;
            }
            const double halfDepth = 0.5 * length / count * meanExtinction(bs0, 0.5 * (bs0 + bs1));
            const double t = t0 + emissionCentroid(halfDepth, x) * (t1 - t0);
            acc.rgb += std::exp(-acc.depth) * -std::expm1(-x) * (c0 + (c1 - c0) * t);
            acc.depth += x;
        }
    }

    const TransferFunction& tf_;
    std::vector<double> breakpoints_;
};

void checkStepRatio(double stepRatio) {
    if (!std::isfinite(stepRatio) || !(stepRatio > 0.0)) {
        throw std::invalid_argument("pre-integration: stepRatio " + std::to_string(stepRatio) +
                                    " is not a finite number above 0");
    }
}

} // namespace

struct SegmentPreintegrator::Impl {
    explicit Impl(const TransferFunction& tf) : integrate(tf) {}
    SegmentIntegrator integrate;
};

SegmentPreintegrator::SegmentPreintegrator(const TransferFunction& tf, double stepRatio)
    : stepRatio_(stepRatio) {
    tf.validate();
    checkStepRatio(stepRatio);
    impl_ = std::make_unique<Impl>(tf);
}

SegmentPreintegrator::~SegmentPreintegrator() = default;

glm::dvec4 SegmentPreintegrator::operator()(double sf, double sb) const {
    return impl_->integrate(sf, sb, stepRatio_);
}

glm::dvec4 preintegrateSegment(const TransferFunction& tf, double sf, double sb, double stepRatio) {
    tf.validate();
    checkStepRatio(stepRatio);
    if (!std::isfinite(sf) || !std::isfinite(sb)) {
        throw std::invalid_argument("pre-integration: the segment's values are not finite");
    }
    return SegmentIntegrator(tf)(sf, sb, stepRatio);
}

PreintegrationTable buildPreintegrationTable(const TransferFunction& tf, double lo, double hi,
                                             int size, double stepRatio) {
    tf.validate();
    detail::checkTableRange(lo, hi, size);
    checkStepRatio(stepRatio);
    PreintegrationTable table;
    table.lo = lo;
    table.hi = hi;
    table.size = size;
    table.stepRatio = stepRatio;
    const auto count = static_cast<std::size_t>(size);
    table.rgba.resize(count * count);
    std::vector<double> values(count);
    for (int n = 0; n < size; ++n) {
        values[static_cast<std::size_t>(n)] = n == size - 1 ? hi : lo + n * (hi - lo) / (size - 1);
    }
    const SegmentIntegrator integrate(tf);
    glm::vec4* out = table.rgba.data();
#pragma omp parallel for schedule(dynamic, 1)
    for (int j = 0; j < size; ++j) {
        const auto row = static_cast<std::size_t>(j) * count;
        for (std::size_t i = 0; i < count; ++i) {
            out[row + i] =
                glm::vec4(integrate(values[i], values[static_cast<std::size_t>(j)], stepRatio));
        }
    }
    return table;
}

} // namespace lucent
