// Every ITK include of Lucent: the rigid registration of registerRigid (Registration.h).
#include "core/registration/RegistrationItk_p.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>
#include <vector>

#include <itkCenteredTransformInitializer.h>
#include <itkCommand.h>
#include <itkImage.h>
#include <itkImageMaskSpatialObject.h>
#include <itkImageRegistrationMethodv4.h>
#include <itkMattesMutualInformationImageToImageMetricv4.h>
#include <itkMeanSquaresImageToImageMetricv4.h>
#include <itkMultiThreaderBase.h>
#include <itkRegistrationParameterScalesFromPhysicalShift.h>
#include <itkRegularStepGradientDescentOptimizerv4.h>
#include <itkVersorRigid3DTransform.h>

namespace lucent::detail {

namespace {

using ImageType = itk::Image<float, 3>;
using MaskImageType = itk::Image<unsigned char, 3>;
using MaskType = itk::ImageMaskSpatialObject<3>;
using TransformType = itk::VersorRigid3DTransform<double>;
using OptimizerType = itk::RegularStepGradientDescentOptimizerv4<double>;
using MetricType = itk::ImageToImageMetricv4<ImageType, ImageType>;
using MattesType = itk::MattesMutualInformationImageToImageMetricv4<ImageType, ImageType>;
using MeanSquaresType = itk::MeanSquaresImageToImageMetricv4<ImageType, ImageType>;
using RegistrationType = itk::ImageRegistrationMethodv4<ImageType, ImageType, TransformType>;
using ScalesType = itk::RegistrationParameterScalesFromPhysicalShift<MetricType>;

// The final MI (nats, Mattes: negative) must reach this: unrelated volumes (noise) stay
// near 0, a CT against itself or an MR of the same head is well below -0.2.
constexpr double kMinimumMutualInformation = 0.05;
// Mean squares at the end over what two unrelated volumes would give (their variances
// and the difference of their means): above this the volumes share nothing. A coarse
// check only: the linear interpolation of the moving volume averages away part of its
// variance (of noise more than half), so noise against a CT is not caught; Mattes MI is.
constexpr double kMaximumRelativeMeanSquares = 0.5;

template <class Image> void setGeometry(Image& image, const VolumeGeometry& g) {
    typename Image::RegionType region;
    typename Image::SizeType size;
    typename Image::SpacingType spacing;
    typename Image::PointType origin;
    typename Image::DirectionType direction;
    for (unsigned r = 0; r < 3; ++r) {
        size[r] = static_cast<itk::SizeValueType>(g.dims[static_cast<int>(r)]);
        spacing[r] = g.spacing[static_cast<int>(r)];
        origin[r] = g.origin[static_cast<int>(r)];
        for (unsigned c = 0; c < 3; ++c) {
            direction(r, c) = g.direction[static_cast<int>(c)][static_cast<int>(r)]; // column c
        }
    }
    region.SetSize(size);
    image.SetRegions(region);
    image.SetSpacing(spacing);
    image.SetOrigin(origin);
    image.SetDirection(direction);
    image.Allocate();
}

ImageType::Pointer toItk(const Volume& v) {
    auto image = ImageType::New();
    setGeometry(*image, v.geometry());
    float* out = image->GetBufferPointer();
    visitVoxels(v, [&](auto voxels) {
        std::transform(voxels.begin(), voxels.end(), out,
                       [](auto x) { return static_cast<float>(x); });
    });
    return image;
}

// The fixed-image mask (voxels above `threshold`) and the fraction of voxels in it.
std::pair<MaskType::Pointer, double> maskOf(const ImageType& image, double threshold) {
    auto mask = MaskImageType::New();
    mask->SetRegions(image.GetLargestPossibleRegion());
    mask->CopyInformation(&image);
    mask->Allocate();
    const float* in = image.GetBufferPointer();
    unsigned char* out = mask->GetBufferPointer();
    const std::size_t n = image.GetLargestPossibleRegion().GetNumberOfPixels();
    std::size_t inside = 0;
    for (std::size_t i = 0; i < n; ++i) {
        out[i] = in[i] > threshold ? 1 : 0;
        inside += out[i];
    }
    auto spatial = MaskType::New();
    spatial->SetImage(mask);
    spatial->Update();
    return {spatial,
            static_cast<double>(inside) / static_cast<double>(std::max<std::size_t>(n, 1))};
}

// Mean and variance of the voxels (of the fixed image: those above `threshold`).
std::pair<double, double> meanVariance(const ImageType& image, std::optional<double> threshold) {
    const float* in = image.GetBufferPointer();
    const std::size_t n = image.GetLargestPossibleRegion().GetNumberOfPixels();
    double sum = 0.0, sum2 = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!threshold || in[i] > *threshold) {
            sum += in[i];
            sum2 += static_cast<double>(in[i]) * in[i];
            ++count;
        }
    }
    const double mean = count ? sum / static_cast<double>(count) : 0.0;
    return {mean, count ? sum2 / static_cast<double>(count) - mean * mean : 0.0};
}

// Clamps the voxels to the 0.5th..99.5th percentile of those above `threshold` (every 31st
// voxel): Mattes MI spreads its bins over the intensity range, and a CT's padding (-3024)
// or a few metal voxels would leave the anatomy one or two bins.
void clampToPercentiles(ImageType& image, std::optional<double> threshold) {
    float* data = image.GetBufferPointer();
    const std::size_t n = image.GetLargestPossibleRegion().GetNumberOfPixels();
    std::vector<float> sample;
    for (std::size_t i = 0; i < n; i += 31) {
        if (!threshold || data[i] > *threshold) {
            sample.push_back(data[i]);
        }
    }
    if (sample.size() < 100) {
        return;
    }
    std::sort(sample.begin(), sample.end());
    const float lo = sample[sample.size() / 200];
    const float hi = sample[sample.size() - 1 - sample.size() / 200];
    if (!(lo < hi)) {
        return;
    }
    std::transform(data, data + n, data, [&](float v) { return std::clamp(v, lo, hi); });
}

// Per level: shrink the in-plane axes by 4/2/1 and an axis only as far as it stays no
// coarser than the shrunk finest axis (5 mm slices of a 0.7 mm CT are not shrunk).
RegistrationType::ShrinkFactorsPerDimensionContainerType shrinkFor(const VolumeGeometry& g,
                                                                   unsigned factor) {
    const double finest = std::min({g.spacing.x, g.spacing.y, g.spacing.z});
    RegistrationType::ShrinkFactorsPerDimensionContainerType s;
    for (unsigned d = 0; d < 3; ++d) {
        const double want = factor * finest / g.spacing[static_cast<int>(d)];
        s[d] = static_cast<unsigned>(std::clamp(std::floor(want + 0.5), 1.0, double(factor)));
    }
    return s;
}

glm::dmat4 toMatrix(const TransformType& t) {
    glm::dmat4 m(1.0);
    const auto& a = t.GetMatrix();
    const auto& offset = t.GetOffset();
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
            m[c][r] = a(static_cast<unsigned>(r), static_cast<unsigned>(c));
        }
        m[3][r] = offset[static_cast<unsigned>(r)];
    }
    return m;
}

} // namespace

RegistrationResult registerRigidItk(const Volume& fixed, const Volume& moving,
                                    const RegistrationOptions& options,
                                    std::optional<double> maskAbove) {
    const auto start = std::chrono::steady_clock::now();
    const std::string name = metricName(options.metric);
    // Every core: ITK's default already, said here so that no caller's setting changes it.
    itk::MultiThreaderBase::SetGlobalDefaultNumberOfThreads(
        std::max(1u, std::thread::hardware_concurrency()));

    const ImageType::Pointer fixedImage = toItk(fixed);
    const ImageType::Pointer movingImage = toItk(moving);

    MetricType::Pointer metric;
    if (options.metric == RegistrationOptions::Metric::MeanSquares) {
        metric = MeanSquaresType::New();
    } else {
        clampToPercentiles(*fixedImage, maskAbove);
        clampToPercentiles(*movingImage, std::nullopt);
        auto mattes = MattesType::New();
        mattes->SetNumberOfHistogramBins(static_cast<itk::SizeValueType>(options.histogramBins));
        metric = mattes;
    }
    double maskFraction = 1.0;
    if (maskAbove) {
        auto [mask, fraction] = maskOf(*fixedImage, *maskAbove);
        if (fraction <= 0.0) {
            throw RegistrationError(name, "no voxel of the fixed volume is above the mask "
                                          "threshold " +
                                              std::to_string(*maskAbove));
        }
        metric->SetFixedImageMask(mask);
        maskFraction = fraction;
    }

    auto transform = TransformType::New();
    using InitializerType = itk::CenteredTransformInitializer<TransformType, ImageType, ImageType>;
    auto initializer = InitializerType::New();
    initializer->SetTransform(transform);
    initializer->SetFixedImage(fixedImage);
    initializer->SetMovingImage(movingImage);
    initializer->GeometryOn();
    initializer->InitializeTransform();

    auto optimizer = OptimizerType::New();
    auto scales = ScalesType::New();
    scales->SetMetric(metric);
    optimizer->SetScalesEstimator(scales);
    optimizer->SetDoEstimateScales(true);
    optimizer->SetDoEstimateLearningRateOnce(true); // per level: first step = max step (mm)
    optimizer->SetRelaxationFactor(0.5);
    optimizer->SetNumberOfIterations(static_cast<itk::SizeValueType>(options.maxIterations));
    optimizer->SetGradientMagnitudeTolerance(1e-10);
    optimizer->SetReturnBestParametersAndValue(false);

    auto registration = RegistrationType::New();
    registration->SetFixedImage(fixedImage);
    registration->SetMovingImage(movingImage);
    registration->SetMetric(metric);
    registration->SetOptimizer(optimizer);
    registration->SetInitialTransform(transform);
    registration->InPlaceOn();

    const unsigned levels = static_cast<unsigned>(options.levels);
    registration->SetNumberOfLevels(levels);
    RegistrationType::SmoothingSigmasArrayType sigmas(levels);
    RegistrationType::MetricSamplingPercentageArrayType percentages(levels);
    for (unsigned l = 0; l < levels; ++l) {
        const unsigned factor = 1u << (levels - 1 - l); // 4, 2, 1
        const auto shrink = shrinkFor(fixed.geometry(), factor);
        registration->SetShrinkFactorsPerDimension(l, shrink);
        sigmas[l] = static_cast<double>(levels - 1 - l); // 2, 1, 0 mm
        double voxels = 1.0;
        for (unsigned d = 0; d < 3; ++d) {
            voxels *= std::ceil(fixed.dims()[static_cast<int>(d)] / double(shrink[d]));
        }
        percentages[l] = std::clamp(options.samplesPerLevel / (voxels * maskFraction), 1e-4, 1.0);
    }
    registration->SetSmoothingSigmasPerLevel(sigmas);
    registration->SetSmoothingSigmasAreSpecifiedInPhysicalUnits(true);
    registration->SetMetricSamplingStrategy(RegistrationType::MetricSamplingStrategyEnum::RANDOM);
    registration->SetMetricSamplingPercentagePerLevel(percentages);
    registration->MetricSamplingReinitializeSeed(static_cast<int>(options.seed % 2147483647u));

    // Progress, cancellation, and the step at which a level has converged: 1/1000 of
    // its first step (the learning rate is estimated at a level's first iteration).
    int iterations = 0;
    auto onIteration = itk::CStyleCommand::New();
    struct Context {
        const RegistrationOptions* options;
        OptimizerType* optimizer;
        RegistrationType* registration;
        int* iterations;
        unsigned levels;
    } context{&options, optimizer.GetPointer(), registration.GetPointer(), &iterations, levels};
    onIteration->SetClientData(&context);
    onIteration->SetCallback([](itk::Object*, const itk::EventObject&, void* data) {
        auto& c = *static_cast<Context*>(data);
        if (c.options->stop.stop_requested()) {
            throw itk::ProcessAborted(__FILE__, __LINE__);
        }
        ++*c.iterations;
        if (c.optimizer->GetCurrentIteration() == 0) {
            c.optimizer->SetMinimumStepLength(1e-3 * c.optimizer->GetLearningRate());
        }
        if (c.options->onProgress) {
            const double level = c.registration->GetCurrentLevel();
            const double within = std::min(1.0, (c.optimizer->GetCurrentIteration() + 1.0) /
                                                    c.optimizer->GetNumberOfIterations());
            c.options->onProgress((level + within) / c.levels, c.optimizer->GetValue());
        }
    });
    optimizer->AddObserver(itk::IterationEvent(), onIteration);

    try {
        if (options.stop.stop_requested()) {
            throw RegistrationCancelled();
        }
        registration->Update();
    } catch (const itk::ProcessAborted&) {
        throw RegistrationCancelled();
    } catch (const itk::ExceptionObject& e) {
        if (options.stop.stop_requested()) {
            throw RegistrationCancelled();
        }
        throw RegistrationError(name, std::string("the metric cannot be evaluated: ") +
                                          e.GetDescription());
    }

    RegistrationResult result;
    result.fixedToMoving = toMatrix(*transform);
    result.metric = optimizer->GetValue();
    result.iterations = iterations;
    result.reason = optimizer->GetStopConditionDescription();
    result.converged = result.reason.find("Maximum number of iterations") == std::string::npos;
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    const auto valid = metric->GetNumberOfValidPoints();
    if (valid < static_cast<itk::SizeValueType>(options.samplesPerLevel / 10)) {
        std::ostringstream why;
        why << "only " << valid << " of about " << options.samplesPerLevel
            << " samples of the fixed volume fall inside the moving one: they barely overlap";
        throw RegistrationError(name, why.str());
    }
    if (options.metric == RegistrationOptions::Metric::MutualInformation) {
        if (!(result.metric < -kMinimumMutualInformation)) {
            std::ostringstream why;
            why << "the mutual information at the end is " << -result.metric << " (at least "
                << kMinimumMutualInformation << " expected): the volumes share no structure";
            throw RegistrationError(name, why.str());
        }
    } else {
        const auto [mf, vf] = meanVariance(*fixedImage, maskAbove);
        const auto [mm, vm] = meanVariance(*movingImage, std::nullopt);
        const double unrelated = vf + vm + (mf - mm) * (mf - mm);
        if (!(unrelated > 0.0) || !(result.metric < kMaximumRelativeMeanSquares * unrelated)) {
            std::ostringstream why;
            why << "the mean squared difference at the end (" << result.metric << ") is "
                << (unrelated > 0.0 ? result.metric / unrelated : 1.0)
                << " of what unrelated volumes give (at most " << kMaximumRelativeMeanSquares
                << " expected): the volumes share no structure";
            throw RegistrationError(name, why.str());
        }
    }
    return result;
}

} // namespace lucent::detail
