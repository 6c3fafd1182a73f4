#pragma once
// Rigid registration of two volumes (ITK behind RegistrationItk.cpp; this header
// shows only Lucent, GLM and std types).

#include <functional>
#include <stdexcept>
#include <stop_token>
#include <string>

#include <glm/glm.hpp>

#include "core/volume/Volume.h"

namespace lucent {

struct RegistrationOptions {
    enum class Metric {
        MutualInformation, // Mattes MI: any two modalities (CT/MR, CT/PET, ...)
        MeanSquares        // the same modality with the same intensities (CT/CT); its check for
                           // unrelated volumes is coarse (noise is not caught)
    };
    Metric metric = Metric::MutualInformation;
    // Rigid only. The affine stage after rigid is not implemented yet: true is refused
    // with std::invalid_argument.
    bool affine = false;
    // Resolution levels: shrink 4/2/1 in-plane (never below the slice spacing),
    // smoothing 2/1/0 mm; fewer levels drop the coarsest first.
    int levels = 3;
    int histogramBins = 50;      // Mattes MI
    int samplesPerLevel = 30000; // random fixed-image samples (inside the mask) per level
    int maxIterations = 200;     // per level
    unsigned seed = 2026;        // the random sampling; the same seed gives the same result
    std::stop_token stop;        // a request ends registerRigid with RegistrationCancelled
    // Called after every optimizer iteration: fraction done (0..1) and the metric.
    std::function<void(double fraction, double metric)> onProgress;
};

const char* metricName(RegistrationOptions::Metric metric); // "Mattes MI", "mean squares"

struct RegistrationResult {
    // Maps a point in the fixed series' patient LPS mm to the same anatomy in the
    // moving series' LPS mm (ITK's convention: the transform of fixed to moving points).
    glm::dmat4 fixedToMoving{1.0};
    double metric = 0.0; // at the end (Mattes MI is negative: lower is better)
    int iterations = 0;  // all levels together
    double seconds = 0.0;
    bool converged = false; // the optimizer stopped on its tolerance, not on maxIterations
    std::string reason;     // the optimizer's stop condition at the last level
};

// Two volumes that cannot be registered: no overlap, no shared structure, a metric that
// cannot be evaluated. what() names the metric and the reason.
struct RegistrationError : std::runtime_error {
    RegistrationError(const std::string& metricName, const std::string& reason);
    std::string metric;
    std::string reason;
};

struct RegistrationCancelled : std::runtime_error {
    RegistrationCancelled() : std::runtime_error("registration cancelled") {}
};

// Versor rigid registration (ITK ImageRegistrationMethodv4): geometry-centred start,
// Mattes MI or mean squares on random samples of the fixed image inside its mask,
// regular-step gradient descent with physical-shift scales, a 3-level pyramid.
// The fixed-image mask leaves out air: for CT (modality "CT", or no modality and a
// minimum below -500) voxels above -500 HU; otherwise voxels above 5 % of the way from
// the minimum to the 99th percentile.
// Throws RegistrationError (see above), RegistrationCancelled, std::invalid_argument
// for an empty volume or bad options.
RegistrationResult registerRigid(const Volume& fixed, const Volume& moving,
                                 const RegistrationOptions& options);

} // namespace lucent
