#include "core/dicom/StackGeometry.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace lucent {
namespace {

constexpr double kDuplicateMm = 1e-3;
// Below this in-plane drift (in pixels) there is nothing worth reporting.
constexpr double kSilentShiftPixels = 0.02;

std::string mm(double v) {
    std::ostringstream s;
    s.precision(3);
    s << std::fixed << v;
    std::string t = s.str();
    while (t.size() > 1 && t.back() == '0') {
        t.pop_back();
    }
    if (t.back() == '.') {
        t.pop_back();
    }
    return t;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// plan.order: the images ascending along the normal n; plan.dropped: those at
// a position already taken.
void orderImages(const StackInput& in, const glm::dvec3& n, StackPlan& plan) {
    std::vector<int> idx(in.positions.size());
    std::iota(idx.begin(), idx.end(), 0);
    // Stable: among equal positions the earlier input (lower InstanceNumber) is kept.
    // (Along n from any one point: the order does not depend on which.)
    std::stable_sort(idx.begin(), idx.end(), [&](int a, int b) {
        return glm::dot(in.positions[a] - in.positions.front(), n) <
               glm::dot(in.positions[b] - in.positions.front(), n);
    });
    for (int i : idx) {
        if (!plan.order.empty() &&
            glm::length(in.positions[i] - in.positions[plan.order.back()]) < kDuplicateMm) {
            plan.dropped.push_back(i);
        } else {
            plan.order.push_back(i);
        }
    }
}

// plan.missingSlices and the warning of a stack resampled at sz mm into nk
// slices because its gaps are uneven.
void describeUnevenGaps(const std::vector<double>& gaps, double typical, double tolerance,
                        double sz, int nk, StackPlan& plan) {
    int missing = 0;
    std::ostringstream list;
    for (std::size_t s = 0; s < gaps.size(); ++s) {
        const double ratio = gaps[s] / typical;
        const long whole = std::lround(ratio);
        if (whole >= 2 && std::abs(ratio - static_cast<double>(whole)) < 0.05) {
            missing += static_cast<int>(whole - 1);
        }
    }
    plan.missingSlices = missing;
    // Runs of equal gaps in one phrase: "6.999 mm after slices 14-26".
    for (std::size_t s = 0; s < gaps.size();) {
        if (std::abs(gaps[s] - typical) <= tolerance) {
            ++s;
            continue;
        }
        std::size_t e = s;
        while (e + 1 < gaps.size() && std::abs(gaps[e + 1] - gaps[s]) <= tolerance) {
            ++e;
        }
        list << (list.tellp() > 0 ? ", " : "") << mm(gaps[s]) << " mm after slice"
             << (e > s ? "s " + std::to_string(s) + "-" + std::to_string(e)
                       : " " + std::to_string(s));
        s = e + 1;
    }
    std::string what = missing > 0 ? std::to_string(missing) + " missing slice(s); " : "";
    plan.warnings.push_back("uneven slice gaps (" + what + "typical " + mm(typical) + " mm; " +
                            list.str() + "): resampled along the normal at " + mm(sz) + " mm, " +
                            std::to_string(nk) +
                            " slices, interpolating linearly between acquired slices");
}

struct Footprint {
    double i0, j0; // its first pixel on the first image's lattice
    int ni, nj;    // pixels
};

// The union of the images' footprints (slice offsets f in the frame of the
// first image, mm), on the first image's pixel lattice.
Footprint footprintOf(const std::vector<glm::dvec3>& f, const StackInput& in) {
    const double sx = in.pixelSpacing.x, sy = in.pixelSpacing.y;
    double uMin = 0.0, uMax = 0.0, wMin = 0.0, wMax = 0.0;
    for (const glm::dvec3& v : f) {
        uMin = std::min(uMin, v.x);
        wMin = std::min(wMin, v.y);
        uMax = std::max(uMax, v.x + (in.columns - 1) * sx);
        wMax = std::max(wMax, v.y + (in.rows - 1) * sy);
    }
    const double i0 = std::floor(uMin / sx + 1e-6);
    const double j0 = std::floor(wMin / sy + 1e-6);
    return {i0, j0, static_cast<int>(std::ceil(uMax / sx - 1e-6) - i0) + 1,
            static_cast<int>(std::ceil(wMax / sy - 1e-6) - j0) + 1};
}

// What keeping the acquired grid would cost: each slice's distance from its
// place on that grid, in plane (in pixels) and along the normal (in spacings).
// Gap variation alone does not bound this: a slow trend of small variations
// adds up along the stack. Slice offsets f in mm from the first; `even` the
// mean gap.
void measureGrid(const std::vector<glm::dvec3>& f, double even, double extent,
                 glm::dvec2 pixelSpacing, StackPlan& plan) {
    double shiftPixels = 0.0;
    double gridDeviation = 0.0;
    for (std::size_t s = 0; s < f.size(); ++s) {
        shiftPixels = std::max(
            {shiftPixels, std::abs(f[s].x) / pixelSpacing.x, std::abs(f[s].y) / pixelSpacing.y});
        gridDeviation = std::max(gridDeviation, std::abs(f[s].z - even * double(s)) / even);
    }
    plan.unevenGaps = gridDeviation > kGridTolerance;
    plan.shiftPixels = shiftPixels;
    plan.gridDeviation = gridDeviation;
    plan.tiltDegrees = glm::degrees(std::atan2(glm::length(glm::dvec2(f.back())), extent));
}

// The warning of a stack kept on its grid although its gaps vary.
std::string gapsVaryWarning(double minGap, double maxGap, double even, double gridDeviation) {
    return "slice gaps vary from " + mm(minGap) + " to " + mm(maxGap) + " mm (" +
           mm(100.0 * (maxGap - minGap) / even) + "% of " + mm(even) + " mm; every slice within " +
           mm(100.0 * gridDeviation) + "% of a spacing of an even " + "grid, tolerance " +
           mm(100.0 * kGridTolerance) + "%): kept the acquired grid";
}

} // namespace

StackPlan planStack(const StackInput& in) {
    StackPlan plan;
    const glm::dvec3 r = glm::normalize(in.rowDir);
    const glm::dvec3 n = glm::normalize(glm::cross(r, in.colDir));
    const glm::dvec3 c = glm::normalize(glm::cross(n, r)); // orthonormal even if IOP is not quite
    const double sx = in.pixelSpacing.x;
    const double sy = in.pixelSpacing.y;

    // Positions in the frame (r, c, n) of the first input image.
    const glm::dvec3 p0 = in.positions.empty() ? glm::dvec3(0.0) : in.positions.front();
    auto frame = [&](const glm::dvec3& p) {
        const glm::dvec3 d = p - p0;
        return glm::dvec3(glm::dot(d, r), glm::dot(d, c), glm::dot(d, n));
    };

    orderImages(in, n, plan);

    const std::size_t count = plan.order.size();
    VolumeGeometry& g = plan.geometry;
    g.direction = glm::dmat3(r, c, n);
    g.dims = {in.columns, in.rows, static_cast<int>(count)};
    if (count == 0) {
        return plan;
    }
    std::vector<glm::dvec3> f(count);
    for (std::size_t s = 0; s < count; ++s) {
        f[s] = frame(in.positions[plan.order[s]]);
    }
    // Re-base on the lowest image along the normal.
    const glm::dvec3 base = f.front();
    for (glm::dvec3& v : f) {
        v -= base;
    }
    const glm::dvec3 first = in.positions[plan.order.front()];

    if (count == 1) {
        g.spacing = {sx, sy, in.sliceThickness > 0.0 ? in.sliceThickness : 1.0};
        g.origin = first;
        plan.placement.assign(1, glm::dvec3(0.0));
        return plan;
    }

    std::vector<double> gaps(count - 1);
    for (std::size_t s = 0; s + 1 < count; ++s) {
        gaps[s] = f[s + 1].z - f[s].z;
    }
    const double extent = f.back().z;
    if (extent < kDuplicateMm * static_cast<double>(count)) {
        plan.error = "images lie in one plane at different in-plane offsets: not a stack";
        return plan;
    }
    const double typical = median(gaps);
    const double minGap = *std::min_element(gaps.begin(), gaps.end());
    const double maxGap = *std::max_element(gaps.begin(), gaps.end());
    const double tolerance = std::max(0.01, 0.01 * typical); // gaps "equal" in the warning text
    const double even = extent / static_cast<double>(count - 1);

    measureGrid(f, even, extent, glm::dvec2(sx, sy), plan);
    const double shiftPixels = plan.shiftPixels, gridDeviation = plan.gridDeviation;
    const bool tilted = shiftPixels > kShiftTolerancePixels;
    if (!tilted) {
        if (shiftPixels > kSilentShiftPixels) {
            plan.warnings.push_back("slices drift " + mm(glm::length(glm::dvec2(f.back()))) +
                                    " mm in plane over " + mm(extent) + " mm (" +
                                    mm(plan.tiltDegrees) + " deg off the normal; at most " +
                                    mm(shiftPixels) + " pixel, tolerance " +
                                    mm(kShiftTolerancePixels) + "): kept the acquired grid");
        }
        for (glm::dvec3& v : f) {
            v.x = v.y = 0.0; // within tolerance: every slice stays on the first one's lattice
        }
    }
    if (!tilted && !plan.unevenGaps && maxGap - minGap > tolerance) {
        plan.warnings.push_back(gapsVaryWarning(minGap, maxGap, even, gridDeviation));
    }

    if (!tilted && !plan.unevenGaps) {
        g.spacing = {sx, sy, even};
        g.origin = first;
        for (std::size_t s = 0; s < count; ++s) {
            plan.placement.emplace_back(0.0, 0.0, static_cast<double>(s));
        }
        return plan;
    }

    plan.resample = true;
    // Along the normal: even gaps keep one grid slice per image; uneven gaps
    // take the smallest gap, so no acquired slice is undersampled (bounded
    // so that a near-duplicate cannot blow the grid up).
    double sz = even;
    int nk = static_cast<int>(count);
    if (plan.unevenGaps) {
        sz = std::max(minGap, extent / (4.0 * static_cast<double>(count)));
        nk = static_cast<int>(std::lround(extent / sz)) + 1;
        sz = extent / static_cast<double>(nk - 1);
    }
    // In the plane: the union of every image's footprint, on the first image's pixel lattice.
    const auto [i0, j0, ni, nj] = footprintOf(f, in);

    g.dims = {ni, nj, nk};
    g.spacing = {sx, sy, sz};
    g.origin = first + r * (i0 * sx) + c * (j0 * sy);
    for (const glm::dvec3& v : f) {
        plan.placement.emplace_back(v.x / sx - i0, v.y / sy - j0, v.z / sz);
    }

    if (tilted) {
        plan.warnings.push_back(
            "gantry tilt " + mm(plan.tiltDegrees) + " deg (slices shift " +
            mm(glm::length(glm::dvec2(f.back()))) + " mm in plane over " + mm(extent) +
            " mm): resampled onto a rectilinear grid along the slice normal, " +
            std::to_string(ni) + "x" + std::to_string(nj) + " pixels to keep every slice whole");
    }
    if (plan.unevenGaps) {
        describeUnevenGaps(gaps, typical, tolerance, sz, nk, plan);
    }
    return plan;
}

} // namespace lucent
