// The ITK part of registerRigid (Registration.h): what both stages share, the rigid
// stage and the checks of the result. The affine stage is in RegistrationItkAffine.cpp.
#include "core/registration/RegistrationItk_p.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <sstream>
#include <thread>
#include <vector>

#include <itkBinShrinkImageFilter.h>
#include <itkCenteredTransformInitializer.h>
#include <itkMattesMutualInformationImageToImageMetricv4.h>
#include <itkMeanSquaresImageToImageMetricv4.h>
#include <itkMultiThreaderBase.h>
#include <itkSmoothingRecursiveGaussianImageFilter.h>

#include "core/registration/RegistrationItkStage_p.h"

namespace lucent::detail {

namespace {

using MattesType = itk::MattesMutualInformationImageToImageMetricv4<ImageType, ImageType>;
using MeanSquaresType = itk::MeanSquaresImageToImageMetricv4<ImageType, ImageType>;

// The final MI (nats, Mattes: negative) must reach this: unrelated volumes (noise) stay
// near 0, a CT against itself or an MR of the same head is well below -0.2.
constexpr double kMinimumMutualInformation = 0.05;
// Mean squares at the end over what two unrelated volumes would give (their variances
// and the difference of their means): above this the volumes share nothing. A coarse
// check only: the linear interpolation of the moving volume averages away part of its
// variance (of noise more than half), so noise against a CT is not caught; Mattes MI is.
constexpr double kMaximumRelativeMeanSquares = 0.5;
// The determinant of the linear part must stay within this and its inverse: an affine
// stage that folds (negative) or shrinks/blows up the volume has diverged.
constexpr double kMinimumDeterminant = 0.5;

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

// `count` random points (LPS mm) of the fixed image inside `mask` (on its grid; all of it
// without one): a voxel drawn at random, kept when inside, moved by up to half a voxel.
// Fewer when the mask is so small that 1000 draws a point do not find them.
SampledPointSetType::Pointer samplePoints(const ImageType& image, const SegmentMask* mask,
                                          int count, std::mt19937& random) {
    auto points = SampledPointSetType::New();
    points->Initialize();
    const auto size = image.GetLargestPossibleRegion().GetSize();
    const std::size_t n = image.GetLargestPossibleRegion().GetNumberOfPixels();
    std::uniform_int_distribution<std::size_t> voxel(0, n - 1);
    std::uniform_real_distribution<double> jitter(-0.5, 0.5);
    itk::ContinuousIndex<double, 3> index;
    ImageType::PointType point;
    SampledPointSetType::PointType stored;
    itk::IdentifierType kept = 0;
    for (std::size_t draw = 0;
         draw < 1000 * std::size_t(count) && kept < itk::IdentifierType(count); ++draw) {
        const std::size_t v = voxel(random);
        if (mask != nullptr && !mask->get(v)) {
            continue;
        }
        index[0] = double(v % size[0]) + jitter(random);
        index[1] = double(v / size[0] % size[1]) + jitter(random);
        index[2] = double(v / (size[0] * size[1])) + jitter(random);
        image.TransformContinuousIndexToPhysicalPoint(index, point);
        stored.CastFrom(point);
        points->SetPoint(kept++, stored);
    }
    return points;
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

using ShrinkFactors = itk::FixedArray<unsigned, 3>;

// Per level: shrink the in-plane axes by 4/2/1 and an axis only as far as it stays no
// coarser than the shrunk finest axis (5 mm slices of a 0.7 mm CT are not shrunk).
ShrinkFactors shrinkFor(const VolumeGeometry& g, unsigned factor) {
    const double finest = std::min({g.spacing.x, g.spacing.y, g.spacing.z});
    ShrinkFactors s;
    for (unsigned d = 0; d < 3; ++d) {
        const double want = factor * finest / g.spacing[static_cast<int>(d)];
        s[d] = static_cast<unsigned>(std::clamp(std::floor(want + 0.5), 1.0, double(factor)));
    }
    return s;
}

// `image` averaged over blocks of `shrink` voxels, then smoothed so that the whole is a
// Gaussian of `sigma` mm (the blocks' own variance taken off).
ImageType::ConstPointer pyramidImage(const ImageType::Pointer& image, const ShrinkFactors& shrink,
                                     double sigma) {
    ImageType::Pointer out = image;
    if (shrink[0] > 1 || shrink[1] > 1 || shrink[2] > 1) {
        auto bin = itk::BinShrinkImageFilter<ImageType, ImageType>::New();
        bin->SetInput(image);
        bin->SetShrinkFactors(shrink);
        bin->Update();
        out = bin->GetOutput();
    }
    if (sigma > 0.0) {
        using SmoothingType = itk::SmoothingRecursiveGaussianImageFilter<ImageType, ImageType>;
        SmoothingType::SigmaArrayType sigmas;
        for (unsigned d = 0; d < 3; ++d) {
            const double h = image->GetSpacing()[d];
            const double block = (double(shrink[d]) * shrink[d] - 1.0) * h * h / 12.0;
            sigmas[d] = std::sqrt(std::max(sigma * sigma - block, 0.01 * sigma * sigma));
        }
        auto smooth = SmoothingType::New();
        smooth->SetInput(out);
        smooth->SetSigmaArray(sigmas);
        smooth->Update();
        out = smooth->GetOutput();
    }
    return out;
}

// The levels 4/2/1 (coarsest first) of both images, smoothing 2/1/0 mm, each with its own
// options.samplesPerLevel points.
std::vector<PyramidLevel> pyramidOf(const ImageType::Pointer& fixed,
                                    const ImageType::Pointer& moving, const VolumeGeometry& g,
                                    const RegistrationOptions& options,
                                    std::vector<SampledPointSetType::Pointer> points) {
    const unsigned levels = static_cast<unsigned>(options.levels);
    std::vector<PyramidLevel> pyramid;
    for (unsigned l = 0; l < levels; ++l) {
        const unsigned factor = 1u << (levels - 1 - l);           // 4, 2, 1
        const double sigma = static_cast<double>(levels - 1 - l); // 2, 1, 0 mm
        const ShrinkFactors shrink = shrinkFor(g, factor);
        PyramidLevel level;
        level.fixed = pyramidImage(fixed, shrink, sigma);
        level.moving = pyramidImage(moving, shrink, sigma);
        level.points = points[l];
        pyramid.push_back(std::move(level));
    }
    return pyramid;
}

} // namespace

MetricType::Pointer makeMetric(const StageSetup& setup, bool finest) {
    MetricType::Pointer metric;
    if (setup.options->metric == RegistrationOptions::Metric::MeanSquares) {
        metric = MeanSquaresType::New();
    } else {
        auto mattes = MattesType::New();
        mattes->SetNumberOfHistogramBins(
            static_cast<itk::SizeValueType>(setup.options->histogramBins));
        metric = mattes;
    }
    // The moving image's gradient: ITK's default, an image of it (a recursive Gaussian of the
    // largest spacing: 5 mm for 5 mm slices, in-plane too) on the coarser levels, where their
    // images are small and its smooth direction widens the capture range; central
    // differences at the samples on the finest level, where that blur would stop short of
    // the optimum and the image (24 bytes a voxel) would take most of the time and memory.
    if (finest) {
        metric->SetUseMovingImageGradientFilter(false);
    }
    return metric;
}

glm::dmat4 toMatrix(const LinearTransformType& t) {
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

void rethrowStageFailure(const RegistrationOptions& options) {
    try {
        throw;
    } catch (const itk::ProcessAborted&) {
        throw RegistrationCancelled();
    } catch (const itk::ExceptionObject& e) {
        if (options.stop.stop_requested()) {
            throw RegistrationCancelled();
        }
        throw RegistrationError(metricName(options.metric),
                                std::string("the metric cannot be evaluated: ") +
                                    e.GetDescription());
    }
}

namespace {

// The rigid stage's start: the geometric centres on each other, or the identity about
// the fixed volume's centre (the two Frames of Reference agree).
RigidTransformType::Pointer initialRigid(const ImageType& fixed, const ImageType& moving,
                                         const VolumeGeometry& fixedGeometry,
                                         RegistrationOptions::Initialisation initialisation) {
    auto transform = RigidTransformType::New();
    if (initialisation == RegistrationOptions::Initialisation::FrameOfReference) {
        const glm::dvec3 c = volumeCentre(fixedGeometry);
        RigidTransformType::CenterType centre;
        for (unsigned d = 0; d < 3; ++d) {
            centre[d] = c[static_cast<int>(d)];
        }
        transform->SetIdentity();
        transform->SetCenter(centre);
        return transform;
    }
    using InitializerType =
        itk::CenteredTransformInitializer<RigidTransformType, ImageType, ImageType>;
    auto initializer = InitializerType::New();
    initializer->SetTransform(transform);
    initializer->SetFixedImage(&fixed);
    initializer->SetMovingImage(&moving);
    initializer->GeometryOn();
    initializer->InitializeTransform();
    return transform;
}

// Throws RegistrationError when the result shows that the volumes do not register:
// too few samples overlap, the metric at the end is no better than for unrelated
// volumes, or the transform folds or blows up the volume.
void checkResult(const RegistrationOptions& options, const StageOutcome& last,
                 const ImageType& fixed, const ImageType& moving, std::optional<double> maskAbove,
                 const glm::dmat4& fixedToMoving) {
    const std::string name = metricName(options.metric);
    if (last.validPoints < static_cast<std::size_t>(options.samplesPerLevel / 10)) {
        std::ostringstream why;
        why << "only " << last.validPoints << " of about " << options.samplesPerLevel
            << " samples of the fixed volume fall inside the moving one: they barely overlap";
        throw RegistrationError(name, why.str());
    }
    if (options.metric == RegistrationOptions::Metric::MutualInformation) {
        if (!(last.value < -kMinimumMutualInformation)) {
            std::ostringstream why;
            why << "the mutual information at the end is " << -last.value << " (at least "
                << kMinimumMutualInformation << " expected): the volumes share no structure";
            throw RegistrationError(name, why.str());
        }
    } else {
        const auto [mf, vf] = meanVariance(fixed, maskAbove);
        const auto [mm, vm] = meanVariance(moving, std::nullopt);
        const double unrelated = vf + vm + (mf - mm) * (mf - mm);
        if (!(unrelated > 0.0) || !(last.value < kMaximumRelativeMeanSquares * unrelated)) {
            std::ostringstream why;
            why << "the mean squared difference at the end (" << last.value << ") is "
                << (unrelated > 0.0 ? last.value / unrelated : 1.0)
                << " of what unrelated volumes give (at most " << kMaximumRelativeMeanSquares
                << " expected): the volumes share no structure";
            throw RegistrationError(name, why.str());
        }
    }
    // An affine stage can fold the volume (a negative determinant) or shrink it to
    // nothing on a pair without enough structure: not a registration.
    const double det = glm::determinant(glm::dmat3(fixedToMoving));
    if (!(det > kMinimumDeterminant && det < 1.0 / kMinimumDeterminant)) {
        std::ostringstream why;
        why << "the transform scales volumes by " << det << " (between " << kMinimumDeterminant
            << " and " << 1.0 / kMinimumDeterminant << " expected): the stage diverged";
        throw RegistrationError(name, why.str());
    }
}

} // namespace

RegistrationResult registerItk(const Volume& fixed, const Volume& moving,
                               const RegistrationOptions& options, std::optional<double> maskAbove,
                               const SegmentMask& mask,
                               RegistrationOptions::Initialisation initialisation) {
    const auto start = std::chrono::steady_clock::now();
    // Every core: ITK's default already, said here so that no caller's setting changes it.
    itk::MultiThreaderBase::SetGlobalDefaultNumberOfThreads(
        std::max(1u, std::thread::hardware_concurrency()));

    const ImageType::Pointer fixedImage = toItk(fixed);
    const ImageType::Pointer movingImage = toItk(moving);
    // The samples, drawn before clamping lifts the air to the lowest tissue value: over the
    // whole fixed volume on the coarser levels (the outline of the body against the air
    // brings a distant start in), inside the mask on the finest (the anatomy decides).
    std::mt19937 random(options.seed);
    std::vector<SampledPointSetType::Pointer> points;
    for (int l = 0; l < options.levels; ++l) {
        const bool finest = l + 1 == options.levels;
        points.push_back(
            samplePoints(*fixedImage, finest ? &mask : nullptr, options.samplesPerLevel, random));
        if (points.back()->GetNumberOfPoints() < std::size_t(options.samplesPerLevel / 10)) {
            std::ostringstream why;
            why << "only " << points.back()->GetNumberOfPoints()
                << " samples of the fixed volume found in its mask (the largest region above "
                << maskAbove.value_or(0.0) << ")";
            throw RegistrationError(metricName(options.metric), why.str());
        }
    }
    if (options.metric == RegistrationOptions::Metric::MutualInformation) {
        clampToPercentiles(*fixedImage, maskAbove);
        clampToPercentiles(*movingImage, std::nullopt);
    }
    StageSetup setup;
    setup.options = &options;
    setup.pyramid =
        pyramidOf(fixedImage, movingImage, fixed.geometry(), options, std::move(points));

    // Progress: each stage gets its share by its number of levels.
    const unsigned rigidLevels = static_cast<unsigned>(options.levels);
    const unsigned affineLevels = options.affine ? std::min(rigidLevels, 2u) : 0u;
    const double rigidShare = double(rigidLevels) / double(rigidLevels + affineLevels);

    RegistrationResult result;
    result.initialisation = initialisation;
    const RigidTransformType::Pointer rigid =
        initialRigid(*fixedImage, *movingImage, fixed.geometry(), initialisation);
    StageOutcome last = runStage(setup, {rigidLevels, 0.0, rigidShare}, *rigid);
    result.rigidFixedToMoving = toMatrix(*rigid);
    result.fixedToMoving = result.rigidFixedToMoving;
    result.iterations = last.iterations;
    // Checked before the affine stage too: a pair that does not register rigidly is
    // refused without the affine stage's time.
    checkResult(options, last, *fixedImage, *movingImage, maskAbove, result.fixedToMoving);
    if (options.affine) {
        last = runAffineStage(setup, {affineLevels, rigidShare, 1.0}, *rigid, result.fixedToMoving);
        result.affine = true;
        result.iterations += last.iterations;
        checkResult(options, last, *fixedImage, *movingImage, maskAbove, result.fixedToMoving);
    }
    result.metric = last.value;
    result.reason = last.reason;
    result.converged = result.reason.find("Maximum number of iterations") == std::string::npos;
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

} // namespace lucent::detail
