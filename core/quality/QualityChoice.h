#pragma once
// Quality chosen from a measured front: a named level (fast, balanced, best)
// or a target time per frame picks the most accurate setting of the front
// that renders within that time; while the user drags, a coarser step of the
// same filter that fits the fast budget.
//
// The levels are time budgets per frame at the image size asked for:
//   fast      50 ms  (20 frames a second: what dragging needs)
//   balanced 250 ms  (a still frame that follows the hand without a wait)
//   best    2000 ms  (a still frame worth waiting two seconds for)

#include <algorithm>
#include <string>
#include <vector>

#include "core/quality/InteractiveQuality.h"
#include "core/quality/QualityFront.h"

namespace lucent {

inline constexpr double kFastBudgetMs = 50.0;
inline constexpr double kBalancedBudgetMs = 250.0;
inline constexpr double kBestBudgetMs = 2000.0;

struct QualityRequest {
    std::string name; // "fast", "balanced", "best" or "120ms"
    double budgetMs = kBalancedBudgetMs;
};

// Parses "fast", "balanced", "best" or a time per frame such as "120ms"
// (a bare number is milliseconds too). Throws std::invalid_argument naming
// the text when it is none of these or not a positive finite time.
QualityRequest parseQualityRequest(const std::string& text);

// A front's times at the size asked for: a fixed part per frame (dispatch,
// read-back, threads) and a part that grows with the pixels.
struct TimeModel {
    double scale = 1.0;   // requested pixels over measured pixels
    double fixedMs = 0.0; // the part that does not grow with the pixels
    double predict(double measuredMs) const {
        const double fixed = std::min(fixedMs, measuredMs);
        return fixed + (measuredMs - fixed) * scale;
    }
};

struct QualityChoice {
    QualitySetting setting;   // what to render with
    double predictedMs = 0.0; // the front's time scaled to the requested image size
    double psnrDb = 0.0;      // the front's PSNR for this setting
    bool fromFront = false;   // false: the front had no point for this shading
    bool withinBudget = false;
    std::string message; // why the budget could not be met, or there was no front
};

// The most accurate front point (`pareto` set, same shading) whose time at
// the requested size (`time`) is within `budgetMs`.
// None that fast: the fastest front point, with a message. No front point for
// this shading: the default setting (with that shading) and a message.
QualityChoice chooseQuality(const std::vector<QualityPoint>& points, double budgetMs, bool shading,
                            const TimeModel& time = {});

// While dragging: the frame is `imageDivisor` smaller on each side and the
// step grows by a factor; the factor is that of the most accurate measured
// point of the still setting's filter and classification (a step at least the
// still one) that fits `budgetMs` at the drag size, else the coarsest such
// point. Without such points: a step factor of 2.
InteractiveQuality chooseInteractive(const std::vector<QualityPoint>& points,
                                     const QualitySetting& still, double budgetMs, TimeModel time,
                                     int imageDivisor = 2);

// "linear step 0.5 post, ~120 ms, 38.8 dB" for status lines and --stats.
std::string describeChoice(const QualityChoice& choice);

} // namespace lucent
