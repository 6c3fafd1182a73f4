#include "core/quality/MeasuredFront.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace lucent {

namespace {

std::uint64_t fnv1a(const void* data, std::size_t n, std::uint64_t h = 1469598103934665603ull) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
        h = (h ^ p[i]) * 1099511628211ull;
    }
    return h;
}

std::string hex(std::uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
    return text;
}

constexpr const char* kMagic = "# lucent quality front";
// Per setting: the median of at least 3 frames, up to 12 until they took 60 ms.
constexpr int kFrames = 3;
constexpr double kMinTotalMs = 60.0;
// An opacity curve's shape: values to 1/200 of the volume's range, opacities to 0.05.
constexpr double kShapeValueSteps = 200.0;
constexpr double kShapeOpacitySteps = 20.0;
constexpr std::size_t kRangeSamples = 65536;

} // namespace

double MeasuredFront::timeScale(int requestedWidth, int requestedHeight) const {
    return double(requestedWidth) * requestedHeight / (double(std::max(1, width)) * height);
}

std::string volumeFingerprint(const Volume& volume) {
    const VolumeGeometry& g = volume.geometry();
    // A lattice of at most about a million bytes, in runs of 64: quick on
    // gigavoxel volumes, and any real edit of the data moves it.
    const std::span<const std::byte> bytes = volume.bytes();
    const std::size_t run = 64;
    const std::size_t stride = std::max<std::size_t>(run, bytes.size() / 16384);
    std::uint64_t h = fnv1a(&g.dims, sizeof g.dims);
    h = fnv1a(&g.spacing, sizeof g.spacing, h);
    for (std::size_t at = 0; at < bytes.size(); at += stride) {
        h = fnv1a(bytes.data() + at, std::min(run, bytes.size() - at), h);
    }
    char dims[96];
    std::snprintf(dims, sizeof dims, "%dx%dx%d %s", g.dims.x, g.dims.y, g.dims.z,
                  voxelTypeName(volume.type()));
    return volume.seriesUid + " " + dims + " " + hex(h);
}

namespace {

// The finite value range on a lattice of about kRangeSamples voxels, spread
// along each axis (a step through the linear index can hit one column only):
// a full pass would cost a gigavoxel volume a second on every edit.
std::pair<double, double> sampledRange(const Volume& volume) {
    const glm::ivec3 dims = volume.dims();
    const auto along = [](int n, int a, int count) {
        return int((2 * a + 1) * std::int64_t(n) / (2 * count));
    };
    const int per = int(std::cbrt(double(kRangeSamples)));
    const glm::ivec3 count = glm::min(dims, glm::ivec3(per));
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (int c = 0; c < count.z; ++c) {
        for (int b = 0; b < count.y; ++b) {
            for (int a = 0; a < count.x; ++a) {
                const double v = volume.value(along(dims.x, a, count.x), along(dims.y, b, count.y),
                                              along(dims.z, c, count.z));
                if (std::isfinite(v)) {
                    lo = std::min(lo, v);
                    hi = std::max(hi, v);
                }
            }
        }
    }
    return lo <= hi ? std::pair{lo, hi} : std::pair{0.0, 0.0};
}

std::int64_t roundedSteps(double value, double unit) {
    const double steps = value / unit;
    // Beyond +-2^62 every value is one step: no transfer function lives there.
    return std::isfinite(steps) ? std::llround(std::clamp(steps, -4.6e18, 4.6e18)) : 0;
}

} // namespace

std::string opacityShape(const TransferFunction& tf, const Volume& volume) {
    const auto [lo, hi] = sampledRange(volume);
    const double span = hi - lo; // infinite for float volumes from -1e308 to 1e308
    const double unit = std::isfinite(span) ? std::max(span, 1.0) / kShapeValueSteps
                                            : std::numeric_limits<double>::max();
    std::uint64_t h = fnv1a("opacity", 7);
    for (const OpacityPoint& p : tf.opacity) {
        const std::int64_t at[2] = {roundedSteps(p.value, unit),
                                    roundedSteps(p.opacity, 1.0 / kShapeOpacitySteps)};
        h = fnv1a(at, sizeof at, h);
    }
    return hex(h);
}

std::string frontKey(const RenderDescription& d, const std::string& backend) {
    std::string key =
        "renderer=" + std::to_string(kRendererVersion) +
        " sweep=" + std::to_string(kQuickSweepVersion) + " backend=" + backend +
        " mode=" + renderModeName(d.mode) +
        " shading=" + (d.transferFunction.shading.enabled ? "1" : "0") +
        " precision=" + (d.sampling.precision == Precision::Double ? "double" : "float") +
        " leaping=" + (d.sampling.emptySpaceLeaping ? "1" : "0");
    // Where the opacity rises and how steeply decides what leaping and early
    // termination save and how fine a step must be: another preset is another
    // front; the colours are not.
    if (d.mode == RenderMode::Dvr) {
        key += " opacity=" + opacityShape(d.transferFunction, *d.volume);
    }
    return key + " volume=" + volumeFingerprint(*d.volume);
}

std::filesystem::path frontCachePath(const std::filesystem::path& cacheDir,
                                     const std::string& key) {
    return cacheDir / ("quality-front-" + hex(fnv1a(key.data(), key.size())) + ".csv");
}

std::optional<MeasuredFront> loadFront(const std::filesystem::path& cacheDir,
                                       const std::string& key) {
    std::ifstream in(frontCachePath(cacheDir, key));
    if (!in) {
        return std::nullopt;
    }
    MeasuredFront front;
    std::string line;
    // "# lucent quality front WxH fixed_ms=F", "# key", the CSV header, the rows.
    if (!std::getline(in, line) || line.rfind(kMagic, 0) != 0 ||
        std::sscanf(line.c_str() + std::string(kMagic).size(), " %dx%d fixed_ms=%lf", &front.width,
                    &front.height, &front.fixedMs) != 3 ||
        front.width < 1 || front.height < 1 || !(front.fixedMs >= 0.0)) {
        return std::nullopt;
    }
    if (!std::getline(in, line) || line != "# " + key) {
        return std::nullopt;
    }
    front.key = key;
    if (!std::getline(in, line) || line != qualityCsvHeader()) {
        return std::nullopt;
    }
    try {
        while (std::getline(in, line)) {
            if (!line.empty()) {
                front.points.push_back(parseQualityCsvRow(line));
            }
        }
    } catch (const std::invalid_argument&) {
        return std::nullopt;
    }
    if (front.points.empty()) {
        return std::nullopt;
    }
    return front;
}

void saveFront(const std::filesystem::path& cacheDir, const MeasuredFront& front) {
    const std::filesystem::path path = frontCachePath(cacheDir, front.key);
    std::error_code ec;
    std::filesystem::create_directories(cacheDir, ec);
    // Written aside and renamed: a reader never sees half a file.
    const std::filesystem::path partial = path.string() + ".part";
    {
        std::ofstream out(partial, std::ios::trunc);
        out << kMagic << " " << front.width << "x" << front.height << " fixed_ms=" << front.fixedMs
            << "\n"
            << "# " << front.key << "\n"
            << qualityCsvHeader() << "\n";
        for (const QualityPoint& p : front.points) {
            out << qualityCsvRow(p);
        }
        if (!out) {
            throw std::runtime_error("quality front: cannot write " + partial.string());
        }
    }
    std::filesystem::rename(partial, path, ec);
    if (ec) {
        throw std::runtime_error("quality front: cannot write " + path.string() + ": " +
                                 ec.message());
    }
}

MeasuredFront measureQuickFront(const RenderDescription& description, const std::string& backend,
                                const QualityRender& render, const QualityRender& reference,
                                const std::function<void(std::size_t, std::size_t)>& progress) {
    MeasuredFront front;
    front.key = frontKey(description, backend);
    RenderDescription base = description;
    // The quick size keeps the view's aspect, the longer side kQuickFrontSize.
    const double aspect = double(description.width) / std::max(1, description.height);
    front.width =
        aspect >= 1.0 ? kQuickFrontSize : std::max(16, int(std::lround(kQuickFrontSize * aspect)));
    front.height =
        aspect >= 1.0 ? std::max(16, int(std::lround(kQuickFrontSize / aspect))) : kQuickFrontSize;
    base.width = front.width;
    base.height = front.height;
    front.points = measureQuality(base, quickSweep(description.transferFunction.shading.enabled),
                                  render, reference, kFrames, progress, kMinTotalMs);
    // The fastest front point again at twice the size (frames are asked for
    // larger than the quick size, and llvmpipe's tiles make small sizes a poor
    // guide): t = fixed + perPixel * pixels through both sizes. Noise can put
    // it outside [0, t]; it is clamped there.
    const auto fastest =
        std::min_element(front.points.begin(), front.points.end(),
                         [](const QualityPoint& a, const QualityPoint& b) { return a.ms < b.ms; });
    if (fastest != front.points.end()) {
        RenderDescription twice = fastest->setting.applyTo(base);
        twice.width = 2 * base.width;
        twice.height = 2 * base.height;
        RenderResult frame;
        const double largeMs = timeFrames(render, twice, kFrames, kMinTotalMs, frame);
        const double fixed = (4.0 * fastest->ms - largeMs) / 3.0;
        front.fixedMs = std::clamp(fixed, 0.0, fastest->ms);
    }
    return front;
}

} // namespace lucent
