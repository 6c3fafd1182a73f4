#include "core/registration/Registration.h"

#include <cmath>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/registration/RegistrationItk_p.h"
#include "core/segmentation/SegmentEffects.h"

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

// std::invalid_argument naming the first option out of its range.
void checkOptions(const RegistrationOptions& o) {
    const auto bad = [](const char* field, long long value, const char* range) {
        throw std::invalid_argument(std::string("registration: options.") + field + " is " +
                                    std::to_string(value) + ", expected " + range);
    };
    if (o.levels < 1 || o.levels > 3) {
        bad("levels", o.levels, "1..3");
    }
    if (o.samplesPerLevel < 100) {
        bad("samplesPerLevel", o.samplesPerLevel, "at least 100");
    }
    if (o.maxIterations < 1) {
        bad("maxIterations", o.maxIterations, "at least 1");
    }
    if (o.histogramBins < 5) {
        bad("histogramBins", o.histogramBins, "at least 5");
    }
    using Metric = RegistrationOptions::Metric;
    if (o.metric != Metric::MutualInformation && o.metric != Metric::MeanSquares) {
        bad("metric", static_cast<long long>(o.metric), "MutualInformation or MeanSquares");
    }
    using Init = RegistrationOptions::Initialisation;
    if (o.initialisation != Init::Auto && o.initialisation != Init::Centres &&
        o.initialisation != Init::FrameOfReference) {
        bad("initialisation", static_cast<long long>(o.initialisation),
            "Auto, Centres or FrameOfReference");
    }
}

} // namespace

const char* metricName(RegistrationOptions::Metric metric) {
    return metric == RegistrationOptions::Metric::MeanSquares ? "mean squares" : "Mattes MI";
}

RegistrationError::RegistrationError(const std::string& metricName_, const std::string& reason_)
    : std::runtime_error("registration (" + metricName_ + ") failed: " + reason_),
      metric(metricName_), reason(reason_) {}

const char* initialisationName(RegistrationOptions::Initialisation initialisation) {
    switch (initialisation) {
    case RegistrationOptions::Initialisation::Centres:
        return "geometric centres";
    case RegistrationOptions::Initialisation::FrameOfReference:
        return "Frame of Reference";
    case RegistrationOptions::Initialisation::Auto:
        break;
    }
    return "auto";
}

RegistrationResult registerRigid(const Volume& fixed, const Volume& moving,
                                 const RegistrationOptions& options) {
    if (fixed.empty() || moving.empty()) {
        throw std::invalid_argument("registration: the fixed or the moving volume is empty");
    }
    checkOptions(options);
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
    // Auto: the scanner's frame when both series come from it (one session), else centring.
    auto initialisation = options.initialisation;
    if (initialisation == RegistrationOptions::Initialisation::Auto) {
        const bool sameFrame = !fixed.frameOfReferenceUid.empty() &&
                               fixed.frameOfReferenceUid == moving.frameOfReferenceUid;
        initialisation = sameFrame ? RegistrationOptions::Initialisation::FrameOfReference
                                   : RegistrationOptions::Initialisation::Centres;
    }
    // The body alone: the largest island above the threshold leaves out the table (and
    // cables, cushions) that lie apart from it and need not move with the patient.
    const SegmentMask body =
        keepLargestIsland(thresholdMask(fixed, std::nextafter(*maskAbove, HUGE_VAL), HUGE_VAL));
    return detail::registerItk(fixed, moving, options, maskAbove, body, initialisation);
}

} // namespace lucent
