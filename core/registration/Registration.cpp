#include "core/registration/Registration.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "core/registration/RegistrationItk_p.h"

namespace lucent {

namespace {

// CT: its modality, or (a file without one) a minimum that only Hounsfield units reach.
bool looksLikeCt(const Volume& v, double minimum) {
    return v.modality == "CT" || (v.modality.empty() && minimum < -500.0);
}

// The 99th percentile from every 97th voxel (enough for a threshold, and quick).
double upperPercentile(const Volume& v) {
    std::vector<float> sample;
    visitVoxels(v, [&](auto voxels) {
        sample.reserve(voxels.size() / 97 + 1);
        for (std::size_t n = 0; n < voxels.size(); n += 97) {
            sample.push_back(static_cast<float>(voxels[n]));
        }
    });
    const auto at = sample.begin() + static_cast<std::ptrdiff_t>(sample.size() * 99 / 100);
    std::nth_element(sample.begin(), at, sample.end());
    return *at;
}

} // namespace

const char* metricName(RegistrationOptions::Metric metric) {
    return metric == RegistrationOptions::Metric::MeanSquares ? "mean squares" : "Mattes MI";
}

RegistrationError::RegistrationError(const std::string& metricName_, const std::string& reason_)
    : std::runtime_error("registration (" + metricName_ + ") failed: " + reason_),
      metric(metricName_), reason(reason_) {}

RegistrationResult registerRigid(const Volume& fixed, const Volume& moving,
                                 const RegistrationOptions& options) {
    if (fixed.empty() || moving.empty()) {
        throw std::invalid_argument("registration: the fixed or the moving volume is empty");
    }
    if (options.affine) {
        throw std::invalid_argument("registration: the affine stage is not implemented yet");
    }
    if (options.levels < 1 || options.levels > 3 || options.samplesPerLevel < 100 ||
        options.maxIterations < 1 || options.histogramBins < 5) {
        throw std::invalid_argument("registration: levels must be 1..3, samplesPerLevel at "
                                    "least 100, maxIterations at least 1, bins at least 5");
    }
    const auto [lo, hi] = fixed.valueRange();
    if (lo == hi) {
        throw RegistrationError(metricName(options.metric),
                                "the fixed volume is uniform (every voxel " + std::to_string(lo) +
                                    "): nothing to align");
    }
    // The mask leaves out air: it would outnumber the anatomy in the samples.
    std::optional<double> maskAbove;
    if (looksLikeCt(fixed, lo)) {
        maskAbove = -500.0;
    } else {
        maskAbove = lo + 0.05 * (upperPercentile(fixed) - lo);
    }
    return detail::registerRigidItk(fixed, moving, options, maskAbove);
}

} // namespace lucent
