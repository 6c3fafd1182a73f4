#include "core/followup/Recist.h"

#include <algorithm>
#include <cstdio>
#include <map>

namespace lucent {

namespace {

constexpr double kToleranceMm = 1e-6;
constexpr double kNodeNormalMm = 10.0;

std::string mm(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f mm", v);
    return buffer;
}

std::string percent(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%+.1f %%", v);
    return buffer;
}

// The lesions of every timepoint by tracking UID, in order of first appearance.
std::vector<LesionRow> rowsOf(const std::vector<TimepointMeasurements>& timepoints) {
    std::vector<LesionRow> rows;
    std::map<std::string, std::size_t> index;
    for (std::size_t t = 0; t < timepoints.size(); ++t) {
        for (const LesionObservation& o : timepoints[t].lesions) {
            auto [it, added] = index.emplace(o.trackingUid, rows.size());
            if (added) {
                LesionRow row;
                row.trackingUid = o.trackingUid;
                row.name = o.name;
                row.role = o.role;
                row.lymphNode = o.lymphNode;
                row.firstTimepoint = t;
                row.at.resize(timepoints.size());
                rows.push_back(std::move(row));
            }
            std::optional<LesionObservation>& cell = rows[it->second].at[t];
            if (!cell) {
                cell = o;
            }
        }
    }
    // Targets first, then non-targets; each in order of first appearance.
    std::stable_sort(rows.begin(), rows.end(), [](const LesionRow& a, const LesionRow& b) {
        return (a.role == LesionRole::Target) > (b.role == LesionRole::Target);
    });
    return rows;
}

void assessFollowUp(const std::vector<LesionRow>& rows, std::size_t t,
                    const std::vector<TimepointAssessment>& before, TimepointAssessment& out) {
    const TimepointAssessment& baseline = before.front();
    bool anyTarget = false;
    bool allGone = true; // every target at CR size
    bool nonTargetPersists = false;
    std::vector<std::string> newLesions;
    std::vector<std::string> notMeasured;
    for (const LesionRow& row : rows) {
        const std::optional<LesionObservation>& o = row.at[t];
        if (row.firstTimepoint == t) {
            newLesions.push_back(row.name);
            continue;
        }
        if (row.firstTimepoint != 0) {
            continue; // new at an earlier follow-up: said there
        }
        if (row.role == LesionRole::NonTarget) {
            nonTargetPersists = nonTargetPersists || o.has_value();
            continue;
        }
        anyTarget = true;
        if (!o) {
            notMeasured.push_back(row.name);
            continue;
        }
        out.sumMm += o->diameterMm;
        const bool crSize = row.lymphNode ? o->diameterMm < kNodeNormalMm - kToleranceMm
                                          : o->diameterMm <= kToleranceMm;
        allGone = allGone && crSize;
    }
    out.evaluable = notMeasured.empty();
    for (const TimepointAssessment& earlier : before) {
        if (earlier.evaluable && (!out.nadirMm || earlier.sumMm < *out.nadirMm)) {
            out.nadirMm = earlier.sumMm;
        }
    }
    if (baseline.sumMm > 0.0) {
        out.fromBaselinePercent = (out.sumMm - baseline.sumMm) / baseline.sumMm * 100.0;
    }
    if (out.nadirMm && *out.nadirMm > 0.0) {
        out.fromNadirPercent = (out.sumMm - *out.nadirMm) / *out.nadirMm * 100.0;
    }

    for (const std::string& name : newLesions) {
        out.reasons.push_back("new lesion: " + name);
    }
    const double overNadir = out.nadirMm ? out.sumMm - *out.nadirMm : 0.0;
    const bool sumProgressed = anyTarget && out.nadirMm &&
                               overNadir >= 0.2 * *out.nadirMm - kToleranceMm &&
                               overNadir >= 5.0 - kToleranceMm;
    if (sumProgressed) {
        out.reasons.push_back(
            "sum " + mm(out.sumMm) + ", " + mm(overNadir) + " (" +
            (out.fromNadirPercent ? percent(*out.fromNadirPercent) : std::string("from 0")) +
            ") over the nadir " + mm(*out.nadirMm));
    }
    if (!newLesions.empty() || sumProgressed) {
        out.response = RecistResponse::PD;
        return;
    }
    if (!anyTarget) {
        out.response = RecistResponse::NE;
        out.reasons.push_back("no target lesion at baseline");
        return;
    }
    if (!notMeasured.empty()) {
        out.response = RecistResponse::NE;
        for (const std::string& name : notMeasured) {
            out.reasons.push_back("target lesion not measured: " + name);
        }
        return;
    }
    if (allGone) {
        out.response = nonTargetPersists ? RecistResponse::PR : RecistResponse::CR;
        out.reasons.push_back(nonTargetPersists ? "target lesions gone, non-target lesions persist"
                                                : "target lesions gone (lymph nodes under 10 mm)");
        return;
    }
    if (out.sumMm - baseline.sumMm <= -0.3 * baseline.sumMm + kToleranceMm) {
        out.response = RecistResponse::PR;
        out.reasons.push_back("sum " + percent(*out.fromBaselinePercent) + " from baseline");
        return;
    }
    out.response = RecistResponse::SD;
}

} // namespace

std::optional<LesionObservation> lesionObservationOf(const Measurement& m,
                                                     const LesionLocation& where) {
    if (m.lesion.role == LesionRole::None || m.lesion.trackingUid.empty() || !m.complete()) {
        return std::nullopt;
    }
    LesionObservation o;
    o.trackingUid = m.lesion.trackingUid;
    o.name = m.label.empty() ? std::string(measurementKindName(m.kind)) : m.label;
    o.role = m.lesion.role;
    o.lymphNode = m.lesion.lymphNode;
    o.where = where;
    o.where.centre = glm::dvec3(0.0);
    for (const glm::dvec3& p : m.points) {
        o.where.centre += p / static_cast<double>(m.points.size());
    }
    switch (m.kind) {
    case MeasurementKind::Distance:
        (m.lesion.lymphNode ? o.shortAxisMm : o.longAxisMm) = measurementLengthMm(m);
        break;
    case MeasurementKind::Bidirectional:
        o.longAxisMm = bidirectionalLongAxisMm(m);
        o.shortAxisMm = bidirectionalShortAxisMm(m);
        break;
    case MeasurementKind::Ellipse: {
        const EllipseRoi e = measurementEllipse(m);
        o.longAxisMm = 2.0 * std::max(e.radiusU, e.radiusV);
        o.shortAxisMm = 2.0 * std::min(e.radiusU, e.radiusV);
        break;
    }
    case MeasurementKind::Arrow:
        o.gone = m.lesion.role == LesionRole::Target;
        break;
    case MeasurementKind::Angle:
    case MeasurementKind::CobbAngle:
        return std::nullopt;
    }
    o.diameterMm = m.lesion.lymphNode ? o.shortAxisMm : o.longAxisMm;
    return o;
}

const char* recistResponseName(RecistResponse r) {
    switch (r) {
    case RecistResponse::Baseline:
        return "Baseline";
    case RecistResponse::CR:
        return "CR";
    case RecistResponse::PR:
        return "PR";
    case RecistResponse::SD:
        return "SD";
    case RecistResponse::PD:
        return "PD";
    case RecistResponse::NE:
        return "NE";
    }
    return "";
}

FollowUpTable assessRecist(std::vector<TimepointMeasurements> timepoints) {
    std::stable_sort(timepoints.begin(), timepoints.end(),
                     [](const TimepointMeasurements& a, const TimepointMeasurements& b) {
                         return a.studyDate < b.studyDate;
                     });
    FollowUpTable table;
    table.lesions = rowsOf(timepoints);
    for (std::size_t t = 0; t < timepoints.size(); ++t) {
        TimepointAssessment a;
        a.studyDate = timepoints[t].studyDate;
        a.studyUids = timepoints[t].studyUids;
        if (t == 0) {
            for (const LesionRow& row : table.lesions) {
                if (row.role == LesionRole::Target && row.at[0]) {
                    a.sumMm += row.at[0]->diameterMm;
                }
            }
            a.response = RecistResponse::Baseline;
        } else {
            assessFollowUp(table.lesions, t, table.timepoints, a);
        }
        table.timepoints.push_back(std::move(a));
    }
    return table;
}

std::vector<const LesionRow*> lesionsBefore(const FollowUpTable& table,
                                            const std::string& studyDate) {
    std::vector<const LesionRow*> out;
    for (const LesionRow& row : table.lesions) {
        if (studyDate.empty() || table.timepoints[row.firstTimepoint].studyDate < studyDate) {
            out.push_back(&row);
        }
    }
    return out;
}

} // namespace lucent
