#pragma once
// One stage of registerRigid (rigid or affine) with ITK's v4 metrics and optimizer,
// private to core/registration: included only by RegistrationItk.cpp (the rigid stage and
// what both share) and RegistrationItkAffine.cpp (the affine stage), each instantiating
// runStage for its transform.

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <itkCommand.h>
#include <itkIdentityTransform.h>
#include <itkImage.h>
#include <itkImageToImageMetricv4.h>
#include <itkMatrixOffsetTransformBase.h>
#include <itkRegistrationParameterScalesFromPhysicalShift.h>
#include <itkRegularStepGradientDescentOptimizerv4.h>
#include <itkVersorRigid3DTransform.h>

#include "core/registration/Registration.h"

namespace lucent::detail {

using ImageType = itk::Image<float, 3>;
using MetricType = itk::ImageToImageMetricv4<ImageType, ImageType>;
using SampledPointSetType = MetricType::FixedSampledPointSetType;
using OptimizerType = itk::RegularStepGradientDescentOptimizerv4<double>;
using ScalesType = itk::RegistrationParameterScalesFromPhysicalShift<MetricType>;
using RigidTransformType = itk::VersorRigid3DTransform<double>;
using LinearTransformType = itk::MatrixOffsetTransformBase<double, 3, 3>;

// One level of the multi-resolution pyramid: both images binned (block means) by the same
// factors and then smoothed, so that the smoothing and the metric's gradient image are
// computed on the small images (ImageRegistrationMethodv4's pyramid smooths and
// differentiates the full images at every level), and the level's random points.
struct PyramidLevel {
    ImageType::ConstPointer fixed;
    ImageType::ConstPointer moving;
    SampledPointSetType::Pointer points; // fixed LPS mm (the finest level's inside the mask)
};

// What every stage shares: the pyramid (intensities already clamped for MI).
struct StageSetup {
    const RegistrationOptions* options = nullptr;
    std::vector<PyramidLevel> pyramid; // coarsest first; a stage of n levels takes the last n
};

// A stage's pyramid and its share of the progress.
struct StagePart {
    unsigned levels = 3;       // of setup.pyramid, the finest `levels`
    double progressFrom = 0.0; // the fraction reported at its start
    double progressTo = 1.0;   // ... and at its end
};

struct StageOutcome {
    int iterations = 0;          // all levels together
    double value = 0.0;          // the metric at the end
    std::string reason;          // the optimizer's stop condition at the last level
    std::size_t validPoints = 0; // samples of the last evaluation inside the moving image
};

// Defined in RegistrationItk.cpp. makeMetric: `finest` for the last level of the pyramid.
MetricType::Pointer makeMetric(const StageSetup& setup, bool finest);
glm::dmat4 toMatrix(const LinearTransformType& t);
// Throws RegistrationCancelled or RegistrationError for the ITK exception being handled.
[[noreturn]] void rethrowStageFailure(const RegistrationOptions& options);

// Defined in RegistrationItkAffine.cpp: the affine stage started from `rigid`; its
// matrix goes to `fixedToMoving`.
StageOutcome runAffineStage(const StageSetup& setup, const StagePart& part,
                            const RigidTransformType& rigid, glm::dmat4& fixedToMoving);

// After every iteration: cancellation (itk::ProcessAborted out of the optimizer), progress,
// and the step at which a level has converged: 0.3 % of its first step, which is one voxel
// of the level (the learning rate is estimated at a level's first iteration); 0.1 % took a
// third more iterations for no better TRE.
struct IterationObserver {
    const RegistrationOptions* options = nullptr;
    OptimizerType* optimizer = nullptr;
    StagePart part;
    unsigned level = 0; // of the stage
    int iterations = 0; // of the stage so far

    void operator()() {
        if (options->stop.stop_requested()) {
            throw itk::ProcessAborted(__FILE__, __LINE__);
        }
        ++iterations;
        if (optimizer->GetCurrentIteration() == 0) {
            optimizer->SetMinimumStepLength(3e-3 * optimizer->GetLearningRate());
        }
        if (options->onProgress) {
            const double within = std::min(1.0, (optimizer->GetCurrentIteration() + 1.0) /
                                                    optimizer->GetNumberOfIterations());
            const double done = (level + within) / part.levels;
            options->onProgress(part.progressFrom + done * (part.progressTo - part.progressFrom),
                                optimizer->GetValue());
        }
    }
};

// One level of a stage on `transform` (optimised in place): the metric of setup.options on
// the level's points, regular-step gradient descent with physical-shift scales, driven
// here (ImageRegistrationMethodv4 would copy the virtual domain and draw its samples over
// every voxel at every level). `observer` counts on from the stage's previous levels.
template <class Transform>
StageOutcome runLevel(const StageSetup& setup, const PyramidLevel& images,
                      IterationObserver& observer, Transform& transform) {
    const RegistrationOptions& options = *setup.options;
    const MetricType::Pointer metric = makeMetric(setup, &images == &setup.pyramid.back());
    metric->SetFixedImage(images.fixed);
    metric->SetMovingImage(images.moving);
    metric->SetFixedTransform(itk::IdentityTransform<double, 3>::New());
    metric->SetMovingTransform(&transform);
    metric->SetFixedSampledPointSet(images.points);
    metric->SetUseSampledPointSet(true);

    auto optimizer = OptimizerType::New();
    auto scales = ScalesType::New();
    scales->SetMetric(metric);
    optimizer->SetMetric(metric);
    optimizer->SetScalesEstimator(scales);
    optimizer->SetDoEstimateScales(true);
    optimizer->SetDoEstimateLearningRateOnce(true); // first step = max step (one voxel)
    optimizer->SetRelaxationFactor(0.5);
    optimizer->SetNumberOfIterations(static_cast<itk::SizeValueType>(options.maxIterations));
    optimizer->SetGradientMagnitudeTolerance(1e-10);
    optimizer->SetReturnBestParametersAndValue(false);

    observer.optimizer = optimizer.GetPointer();
    auto onIteration = itk::CStyleCommand::New();
    onIteration->SetClientData(&observer);
    onIteration->SetCallback([](itk::Object*, const itk::EventObject&, void* data) {
        (*static_cast<IterationObserver*>(data))();
    });
    optimizer->AddObserver(itk::IterationEvent(), onIteration);
    try {
        if (options.stop.stop_requested()) {
            throw RegistrationCancelled();
        }
        metric->Initialize();
        optimizer->StartOptimization();
    } catch (const itk::ExceptionObject&) {
        rethrowStageFailure(options);
    }
    return {observer.iterations, optimizer->GetValue(), optimizer->GetStopConditionDescription(),
            static_cast<std::size_t>(metric->GetNumberOfValidPoints())};
}

// Runs one stage on `transform` (already initialised; optimised in place), level after
// level of the finest part.levels of the pyramid.
template <class Transform>
StageOutcome runStage(const StageSetup& setup, const StagePart& part, Transform& transform) {
    IterationObserver observer{setup.options, nullptr, part};
    StageOutcome outcome;
    const std::size_t first = setup.pyramid.size() - part.levels;
    for (unsigned l = 0; l < part.levels; ++l) {
        observer.level = l;
        outcome = runLevel(setup, setup.pyramid[first + l], observer, transform);
    }
    return outcome;
}

} // namespace lucent::detail
