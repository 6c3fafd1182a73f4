#include "core/raycast/QualityFront.h"

#include <algorithm>

namespace lucent {

std::string QualitySetting::classificationName() const {
    if (preintegrate) {
        return "preintegrated";
    }
    return classification == Classification::Pre ? "pre" : "post";
}

RenderDescription QualitySetting::applyTo(const RenderDescription& d) const {
    RenderDescription out = d;
    out.sampling.step = step;
    out.sampling.interpolation = interpolation;
    out.sampling.classification = classification;
    out.sampling.preintegrate = preintegrate;
    out.sampling.brickSize = brickSize;
    out.transferFunction.shading.enabled = shading;
    return out;
}

std::vector<QualitySetting> qualitySweep(const std::vector<double>& steps,
                                         const std::vector<int>& brickSizes) {
    std::vector<QualitySetting> out;
    for (const int brick : brickSizes) {
        for (const double step : steps) {
            for (const Interpolation interp :
                 {Interpolation::Nearest, Interpolation::Linear, Interpolation::Cubic}) {
                for (const int c : {0, 1, 2}) { // post, pre, pre-integrated
                    if (c == 1 && interp != Interpolation::Linear) {
                        continue;
                    }
                    for (const bool shading : {true, false}) {
                        QualitySetting s;
                        s.step = step;
                        s.interpolation = interp;
                        s.classification = c == 1 ? Classification::Pre : Classification::Post;
                        s.preintegrate = c == 2;
                        s.shading = shading;
                        s.brickSize = brick;
                        out.push_back(s);
                    }
                }
            }
        }
    }
    return out;
}

RenderDescription qualityReference(const RenderDescription& d) {
    RenderDescription r = d;
    r.sampling.precision = Precision::Double;
    r.sampling.interpolation = Interpolation::Cubic;
    r.sampling.step = 1.0 / 16.0;
    r.sampling.earlyTermination = 1.0;
    return r;
}

void markParetoFront(std::vector<QualityPoint>& points) {
    for (QualityPoint& p : points) {
        p.pareto = std::none_of(points.begin(), points.end(), [&](const QualityPoint& q) {
            if (q.setting.shading != p.setting.shading) {
                return false; // another image, another reference: not comparable
            }
            const bool noWorse = q.ms <= p.ms && q.psnrDb >= p.psnrDb;
            const bool better = q.ms < p.ms || q.psnrDb > p.psnrDb;
            return noWorse && better;
        });
    }
}

std::optional<QualityPoint> bestWithin(const std::vector<QualityPoint>& points, double ms,
                                       bool shading) {
    std::optional<QualityPoint> best, fastest;
    for (const QualityPoint& p : points) {
        if (!p.pareto || p.setting.shading != shading) {
            continue;
        }
        if (!fastest || p.ms < fastest->ms) {
            fastest = p;
        }
        if (p.ms <= ms && (!best || p.psnrDb > best->psnrDb)) {
            best = p;
        }
    }
    return best ? best : fastest;
}

} // namespace lucent
