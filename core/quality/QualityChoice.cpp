#include "core/quality/QualityChoice.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace lucent {

QualityRequest parseQualityRequest(const std::string& text) {
    if (text == "fast") {
        return {text, kFastBudgetMs};
    }
    if (text == "balanced") {
        return {text, kBalancedBudgetMs};
    }
    if (text == "best") {
        return {text, kBestBudgetMs};
    }
    std::string number = text;
    if (number.size() > 2 && number.substr(number.size() - 2) == "ms") {
        number.resize(number.size() - 2);
    }
    std::size_t used = 0;
    double ms = 0.0;
    try {
        ms = std::stod(number, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (number.empty() || used != number.size() || !std::isfinite(ms) || ms <= 0.0) {
        throw std::invalid_argument("quality: '" + text +
                                    "' is not fast, balanced, best or a time per frame such as "
                                    "120ms");
    }
    return {text, ms};
}

QualityChoice chooseQuality(const std::vector<QualityPoint>& points, double budgetMs, bool shading,
                            const TimeModel& time) {
    QualityChoice choice;
    const QualityPoint* best = nullptr;
    const QualityPoint* fastest = nullptr;
    for (const QualityPoint& p : points) {
        if (!p.pareto || p.setting.shading != shading) {
            continue;
        }
        if (!fastest || p.ms < fastest->ms) {
            fastest = &p;
        }
        if (time.predict(p.ms) <= budgetMs && (!best || p.psnrDb > best->psnrDb)) {
            best = &p;
        }
    }
    if (!fastest) {
        choice.setting.shading = shading;
        choice.message = std::string("no measured front for ") + (shading ? "shaded" : "unshaded") +
                         " rendering of this volume; using the default sampling";
        return choice;
    }
    const QualityPoint& chosen = best ? *best : *fastest;
    choice.setting = chosen.setting;
    choice.predictedMs = time.predict(chosen.ms);
    choice.psnrDb = chosen.psnrDb;
    choice.fromFront = true;
    choice.withinBudget = best != nullptr;
    if (!best) {
        char text[160];
        std::snprintf(text, sizeof text,
                      "no setting of the front renders within %.0f ms per frame; using the "
                      "fastest (about %.0f ms)",
                      budgetMs, choice.predictedMs);
        choice.message = text;
    }
    return choice;
}

InteractiveQuality chooseInteractive(const std::vector<QualityPoint>& points,
                                     const QualitySetting& still, double budgetMs, TimeModel time,
                                     int imageDivisor) {
    InteractiveQuality quality;
    const int divisor = std::max(1, imageDivisor);
    quality.imageScale = 1.0 / divisor;
    time.scale /= double(divisor * divisor);
    const QualityPoint* best = nullptr;
    const QualityPoint* coarsest = nullptr;
    for (const QualityPoint& p : points) {
        const QualitySetting& s = p.setting;
        if (s.shading != still.shading || s.interpolation != still.interpolation ||
            s.classification != still.classification || s.preintegrate != still.preintegrate ||
            s.step < still.step) {
            continue;
        }
        if (!coarsest || s.step > coarsest->setting.step) {
            coarsest = &p;
        }
        if (time.predict(p.ms) <= budgetMs && (!best || p.psnrDb > best->psnrDb)) {
            best = &p;
        }
    }
    const QualityPoint* chosen = best ? best : coarsest;
    quality.stepFactor = chosen ? chosen->setting.step / still.step : 2.0;
    return quality;
}

std::string describeChoice(const QualityChoice& choice) {
    char text[200];
    const QualitySetting& s = choice.setting;
    if (!choice.fromFront) {
        std::snprintf(text, sizeof text, "%s step %g %s (default, not measured)",
                      interpolationName(s.interpolation), s.step, s.classificationName().c_str());
    } else {
        std::snprintf(text, sizeof text, "%s step %g %s, ~%.0f ms, %.1f dB",
                      interpolationName(s.interpolation), s.step, s.classificationName().c_str(),
                      choice.predictedMs, choice.psnrDb);
    }
    return text;
}

} // namespace lucent
