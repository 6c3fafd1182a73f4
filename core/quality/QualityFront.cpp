#include "core/quality/QualityFront.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "core/image/ImageMetrics.h"

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

std::vector<QualitySetting> quickSweep(bool shading) {
    std::vector<QualitySetting> out;
    QualitySetting nearest;
    nearest.step = 2.0;
    nearest.interpolation = Interpolation::Nearest;
    nearest.shading = shading;
    out.push_back(nearest);
    for (const Interpolation interp : {Interpolation::Linear, Interpolation::Cubic}) {
        for (const double step : {2.0, 1.0, 0.5, 0.25}) {
            QualitySetting s;
            s.step = step;
            s.interpolation = interp;
            s.shading = shading;
            out.push_back(s);
        }
    }
    // Pre-integrated trilinear: a sharp transfer function (ct-soft-tissue on
    // the Philips CT) reaches 39 dB at step 1 where post-classification needs
    // a step below 0.125.
    for (const double step : {2.0, 1.0, 0.5}) {
        QualitySetting s;
        s.step = step;
        s.preintegrate = true;
        s.shading = shading;
        out.push_back(s);
    }
    return out;
}

namespace {

double medianOf(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

} // namespace

double timeFrames(const QualityRender& render, const RenderDescription& d, int frames,
                  double minTotalMs, RenderResult& last) {
    using Clock = std::chrono::steady_clock;
    last = render(d); // warms tables and uploads
    std::vector<double> ms;
    double total = 0.0;
    const int least = std::max(1, frames);
    for (int n = 0; n < least || (total < minTotalMs && n < 4 * least); ++n) {
        const auto start = Clock::now();
        last = render(d);
        ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        total += ms.back();
    }
    return medianOf(ms);
}

std::vector<QualityPoint>
measureQuality(const RenderDescription& base, const std::vector<QualitySetting>& settings,
               const QualityRender& render, const QualityRender& reference, int frames,
               const std::function<void(std::size_t, std::size_t)>& progress, double minTotalMs) {
    // One reference per shading state: shading is part of what is compared.
    std::optional<ImageRGBA8> refShaded, refFlat;
    std::vector<QualityPoint> points;
    for (const QualitySetting& setting : settings) {
        std::optional<ImageRGBA8>& ref = setting.shading ? refShaded : refFlat;
        if (!ref) {
            RenderDescription r = base;
            r.transferFunction.shading.enabled = setting.shading;
            ref = reference(qualityReference(r)).image;
        }
        const RenderDescription d = setting.applyTo(base);
        QualityPoint p;
        p.setting = setting;
        RenderResult last;
        p.ms = timeFrames(render, d, frames, minTotalMs, last);
        p.samples = last.stats.samples;
        p.psnrDb = psnr(last.image, *ref);
        p.ssim = ssim(last.image, *ref);
        points.push_back(p);
        if (progress) {
            progress(points.size(), settings.size());
        }
    }
    markParetoFront(points);
    return points;
}

std::string qualityCsvHeader() {
    return "step,interp,classification,shading,brick,ms,samples,psnr_db,ssim,pareto";
}

std::string qualityCsvRow(const QualityPoint& p) {
    char psnrText[32];
    if (std::isinf(p.psnrDb)) {
        std::snprintf(psnrText, sizeof psnrText, "inf");
    } else {
        std::snprintf(psnrText, sizeof psnrText, "%.2f", p.psnrDb);
    }
    char row[256];
    std::snprintf(row, sizeof row, "%g,%s,%s,%d,%d,%.2f,%zu,%s,%.4f,%d\n", p.setting.step,
                  interpolationName(p.setting.interpolation),
                  p.setting.classificationName().c_str(), p.setting.shading ? 1 : 0,
                  p.setting.brickSize, p.ms, p.samples, psnrText, p.ssim, p.pareto ? 1 : 0);
    return row;
}

QualityPoint parseQualityCsvRow(const std::string& text) {
    std::string row = text;
    while (!row.empty() && (row.back() == '\n' || row.back() == '\r')) {
        row.pop_back();
    }
    std::vector<std::string> c;
    std::stringstream in(row);
    for (std::string cell; std::getline(in, cell, ',');) {
        c.push_back(cell);
    }
    if (c.size() != 10) {
        throw std::invalid_argument("quality CSV: expected 10 columns, got " +
                                    std::to_string(c.size()) + " in '" + row + "'");
    }
    const char* const names[] = {"step", "interp",  "classification", "shading", "brick",
                                 "ms",   "samples", "psnr_db",        "ssim",    "pareto"};
    const auto number = [&](std::size_t i) {
        std::size_t used = 0;
        double v = 0.0;
        try {
            v = c[i] == "inf" ? HUGE_VAL : std::stod(c[i], &used);
            used = c[i] == "inf" ? c[i].size() : used;
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != c[i].size()) {
            throw std::invalid_argument(std::string("quality CSV: column ") + names[i] + ": '" +
                                        c[i] + "' is not a number");
        }
        return v;
    };
    QualityPoint p;
    p.setting.step = number(0);
    if (c[1] == "nearest") {
        p.setting.interpolation = Interpolation::Nearest;
    } else if (c[1] == "linear") {
        p.setting.interpolation = Interpolation::Linear;
    } else if (c[1] == "cubic") {
        p.setting.interpolation = Interpolation::Cubic;
    } else {
        throw std::invalid_argument("quality CSV: column interp: '" + c[1] + "' is unknown");
    }
    if (c[2] != "post" && c[2] != "pre" && c[2] != "preintegrated") {
        throw std::invalid_argument("quality CSV: column classification: '" + c[2] +
                                    "' is unknown");
    }
    p.setting.classification = c[2] == "pre" ? Classification::Pre : Classification::Post;
    p.setting.preintegrate = c[2] == "preintegrated";
    p.setting.shading = number(3) != 0.0;
    p.setting.brickSize = int(number(4));
    p.ms = number(5);
    p.samples = std::size_t(number(6));
    p.psnrDb = number(7);
    p.ssim = number(8);
    p.pareto = number(9) != 0.0;
    if (!(p.setting.step > 0.0) || p.setting.brickSize < 1 || !(p.ms >= 0.0)) {
        throw std::invalid_argument("quality CSV: step, brick or ms out of range in '" + row + "'");
    }
    return p;
}

} // namespace lucent
