#pragma once
// Rigid, then optionally affine, registration of two volumes (ITK behind
// RegistrationItk*.cpp; this header shows only Lucent, GLM and std types).

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
    // Where the rigid stage starts.
    enum class Initialisation {
        // FrameOfReference when both volumes carry the same non-empty frameOfReferenceUid
        // (one session of one scanner: its patient coordinates already agree), else Centres.
        Auto,
        // The geometric centres of the two volumes on each other (no rotation): another
        // scanner, another session, or files without a Frame of Reference.
        Centres,
        // The identity: the two volumes' patient coordinates are taken as they are,
        // whatever their Frame of Reference UIDs say.
        FrameOfReference
    };
    Initialisation initialisation = Initialisation::Auto;
    // After the rigid stage, an affine one (12 parameters: scaling and shear too),
    // started from the rigid result, same metric, levels min(levels, 2) (shrink 2/1,
    // smoothing 1/0 mm): for a scanner whose scale or gantry differs. Rigid only otherwise.
    bool affine = false;
    // Resolution levels of the rigid stage: shrink 4/2/1 in-plane (never below the slice
    // spacing), smoothing 2/1/0 mm; fewer levels drop the coarsest first.
    int levels = 3;
    int histogramBins = 50;      // Mattes MI
    int samplesPerLevel = 30000; // random fixed-image samples per level (see registerRigid)
    int maxIterations = 200;     // per level (of each stage)
    unsigned seed = 2026;        // the random sampling; the same seed gives the same result
    std::stop_token stop;        // a request ends registerRigid with RegistrationCancelled
    // Called after every optimizer iteration of either stage: fraction done (0..1, over
    // both stages: each gets its share by its number of levels) and the metric.
    std::function<void(double fraction, double metric)> onProgress;
};

const char* metricName(RegistrationOptions::Metric metric); // "Mattes MI", "mean squares"
// "auto", "geometric centres", "Frame of Reference"
const char* initialisationName(RegistrationOptions::Initialisation initialisation);

struct RegistrationResult {
    // Maps a point in the fixed series' patient LPS mm to the same anatomy in the
    // moving series' LPS mm (ITK's convention: the transform of fixed to moving points).
    // The affine stage's matrix when `affine`, else the rigid one.
    glm::dmat4 fixedToMoving{1.0};
    bool affine = false;                // an affine stage ran (options.affine)
    glm::dmat4 rigidFixedToMoving{1.0}; // the rigid stage's result (the affine one's start)
    // The start the rigid stage took: Centres or FrameOfReference (never Auto).
    RegistrationOptions::Initialisation initialisation =
        RegistrationOptions::Initialisation::Centres;
    double metric = 0.0; // at the end (Mattes MI is negative: lower is better)
    int iterations = 0;  // all levels of both stages together
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

// Versor rigid registration (ITK's v4 metrics and optimizer), then an affine stage when
// options.affine: started as options.initialisation says, Mattes MI or mean squares on
// random samples of the fixed image, regular-step gradient descent with physical-shift
// scales, a 3-level pyramid (the 2 finest for the affine stage).
// The finest level's samples lie inside the fixed-image mask, which leaves out air and the
// table: the largest face-connected region of the voxels above -500 HU for CT (modality
// "CT", or no modality and a minimum below -500), otherwise above 5 % of the way from the
// minimum to the 99th percentile (the table lies apart from the body). The coarser levels
// sample the whole volume: the body's outline against the air brings a distant start in.
// Throws RegistrationError (see above; also an affine stage that folds or blows the
// volume up), RegistrationCancelled, std::invalid_argument for an empty volume or bad
// options (naming the option).
RegistrationResult registerRigid(const Volume& fixed, const Volume& moving,
                                 const RegistrationOptions& options);

} // namespace lucent
