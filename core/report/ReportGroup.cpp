#include "core/report/ReportGroup.h"

#include <cmath>

#include "core/report/MeasurementGeometryText.h"

namespace lucent {

namespace {

// The concepts Lucent knows, with their older SNOMED-RT (SRT) codes.
enum class Concept {
    Length,
    LongAxis,
    ShortAxis,
    Angle,
    CobbAngle,
    Area,
    Mean,
    Sd,
    Min,
    Max,
    SuvBw,
    None
};

Concept conceptOf(const ReportNumber& n) {
    struct Known {
        const char* code;
        Concept meaning;
    };
    static const Known known[] = {
        {"410668003", Concept::Length},    {"G-D7FE", Concept::Length},
        {"121206", Concept::Length},       {"103339001", Concept::LongAxis},
        {"G-A185", Concept::LongAxis},     {"103340004", Concept::ShortAxis},
        {"G-A186", Concept::ShortAxis},    {"1483009", Concept::Angle},
        {"285285000", Concept::CobbAngle}, {"42798000", Concept::Area},
        {"G-A166", Concept::Area},         {"373098007", Concept::Mean},
        {"R-00317", Concept::Mean},        {"386136009", Concept::Sd},
        {"R-10047", Concept::Sd},          {"255605001", Concept::Min},
        {"R-404FB", Concept::Min},         {"56851009", Concept::Max},
        {"G-A437", Concept::Max},          {"126401", Concept::SuvBw}};
    for (const Known& k : known) {
        if (n.code == k.code) {
            return k.meaning;
        }
    }
    return Concept::None;
}

std::string describe(const ReportNumber& n) {
    char value[64];
    std::snprintf(value, sizeof value, "%g", n.value);
    return n.meaning + " " + value + " " + n.unit;
}

// A plane through the points: u along the first line, v across it in the plane of
// the first point off that line; the image's plane for a SCOORD.
SlicePlane planeThrough(const ReportRegion& region) {
    if (region.imagePlane) {
        return *region.imagePlane;
    }
    SlicePlane plane;
    const std::vector<glm::dvec3>& p = region.points;
    glm::dvec3 centre(0.0);
    for (const glm::dvec3& q : p) {
        centre += q / static_cast<double>(p.size());
    }
    plane.centre = centre;
    if (p.size() < 2 || glm::length(p[1] - p[0]) <= 0.0) {
        return plane;
    }
    plane.u = glm::normalize(p[1] - p[0]);
    glm::dvec3 normal(0.0);
    for (std::size_t i = 2; i < p.size() && glm::length(normal) < 1e-9; ++i) {
        normal = glm::cross(plane.u, p[i] - p[0]);
    }
    if (glm::length(normal) < 1e-9) { // collinear: any plane holding the line
        const glm::dvec3 other =
            std::abs(plane.u.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
        normal = glm::cross(plane.u, other);
    }
    plane.v = glm::normalize(glm::cross(glm::normalize(normal), plane.u));
    return plane;
}

// Measurement::unit of a UCUM code: HU, SUVbw, Bq/mL, none, an annotation's text.
std::string unitOfUcum(const std::string& ucum) {
    if (ucum == "[hnsf'U]") {
        return "HU";
    }
    if (ucum == "{SUVbw}g/ml") {
        return "SUVbw";
    }
    if (ucum == "Bq/ml") {
        return "Bq/mL";
    }
    if (ucum == "1") {
        return {};
    }
    if (ucum.size() > 2 && ucum.front() == '{' && ucum.back() == '}') {
        return ucum.substr(1, ucum.size() - 2);
    }
    return ucum;
}

// An ellipse's statistics (Area, Mean, SD, Min, Max) and SUVs (SUVbw by its derivation)
// into m; what does not fit an ellipse goes to notShown.
void readStatistics(Measurement& m, const std::vector<const ReportNumber*>& numbers,
                    const std::string& name, std::vector<std::string>& notShown) {
    for (const ReportNumber* n : numbers) {
        const Concept c = conceptOf(*n);
        if (m.kind != MeasurementKind::Ellipse) {
            notShown.push_back(name + ": " + describe(*n));
            continue;
        }
        if (c == Concept::SuvBw) {
            SuvStatistics& suv = m.suv ? *m.suv : m.suv.emplace();
            const std::string& d = n->derivation;
            double* target = d == "56851009" || d == "G-A437"     ? &suv.max
                             : d == "373098007" || d == "R-00317" ? &suv.mean
                             : d == "126031"                      ? &suv.peak
                                                                  : nullptr;
            if (target == nullptr) {
                notShown.push_back(name + ": " + describe(*n));
            } else {
                *target = n->value;
            }
            continue;
        }
        RoiStatistics& s = m.statistics;
        (c == Concept::Area   ? s.areaMm2
         : c == Concept::Mean ? s.mean
         : c == Concept::Sd   ? s.standardDeviation
         : c == Concept::Min  ? s.minimum
                              : s.maximum) = n->value;
        if (c != Concept::Area) {
            m.unit = unitOfUcum(n->unit);
        }
    }
}

const ReportRegion* placedRegion(const ReportNumber& n, std::size_t points) {
    return n.region && n.region->points.size() == points ? &*n.region : nullptr;
}

} // namespace

InterpretedGroup interpretGroup(const ReportGroup& group, bool lucentWrote) {
    InterpretedGroup out;
    const std::string name = group.trackingIdentifier.empty() ? std::string("Measurement group")
                                                              : group.trackingIdentifier;
    if (group.geometry) {
        if (auto decoded = decodeMeasurementGeometry(*group.geometry)) {
            Measurement m = std::move(decoded->measurement);
            m.label = decoded->labelled ? group.trackingIdentifier : std::string();
            m.text = group.comment.value_or(std::string());
            m.readOnly = !lucentWrote;
            m.lesion = group.lesion;
            if (m.complete()) {
                out.measurement = std::move(m);
                for (const std::string& item : group.otherItems) {
                    out.notShown.push_back(name + ": " + item);
                }
                return out;
            }
        }
    }

    Measurement m;
    m.label = group.trackingIdentifier;
    m.readOnly = true;
    m.lesion = group.lesion;
    const ReportNumber* shape = nullptr; // the number whose region gives the points
    const ReportNumber* shortAxis = nullptr;
    std::vector<const ReportNumber*> statistics;
    for (const ReportNumber& n : group.numbers) {
        const Concept c = conceptOf(n);
        const bool ellipse = n.region && n.region->shape == ReportRegion::Shape::Ellipse &&
                             n.region->points.size() == 4;
        const bool statistic = c == Concept::Area || c == Concept::Mean || c == Concept::Sd ||
                               c == Concept::Min || c == Concept::Max || c == Concept::SuvBw;
        if (ellipse && !shape) {
            m.kind = MeasurementKind::Ellipse;
            shape = &n;
            if (statistic) {
                statistics.push_back(&n);
            }
        } else if ((c == Concept::Length || c == Concept::LongAxis) && !shape &&
                   placedRegion(n, 2)) {
            m.kind = c == Concept::LongAxis ? MeasurementKind::Bidirectional
                     : group.comment        ? MeasurementKind::Arrow
                                            : MeasurementKind::Distance;
            shape = &n;
        } else if (c == Concept::ShortAxis && placedRegion(n, 2)) {
            shortAxis = &n;
        } else if (c == Concept::Angle && !shape && placedRegion(n, 3)) {
            m.kind = MeasurementKind::Angle;
            shape = &n;
        } else if (c == Concept::CobbAngle && !shape && placedRegion(n, 4)) {
            m.kind = MeasurementKind::CobbAngle;
            shape = &n;
        } else if (statistic) {
            statistics.push_back(&n);
        } else {
            out.notShown.push_back(name + ": " + describe(n) +
                                   (n.region && !n.region->unplaced.empty()
                                        ? " (" + n.region->unplaced + ")"
                                        : std::string()));
        }
    }
    if (m.kind == MeasurementKind::Bidirectional && !shortAxis) {
        m.kind = MeasurementKind::Distance; // a long axis alone is a length
    }
    if (!shape) {
        for (const ReportNumber* n : statistics) {
            out.notShown.push_back(name + ": " + describe(*n));
        }
        if (group.comment) {
            out.notShown.push_back(name + ": Comment \"" + *group.comment + "\"");
        }
    } else {
        m.points = shape->region->points;
        if (m.kind == MeasurementKind::Bidirectional) {
            m.points.insert(m.points.end(), shortAxis->region->points.begin(),
                            shortAxis->region->points.end());
        } else if (shortAxis) {
            out.notShown.push_back(name + ": " + describe(*shortAxis));
        }
        ReportRegion all = *shape->region; // the plane through every point of the measurement
        all.points = m.points;
        m.plane = planeThrough(all);
        if (m.kind == MeasurementKind::Ellipse) {
            // Lucent's ellipse has its axes along the plane's u and v.
            m.plane.u = glm::normalize(m.points[1] - m.points[0]);
            m.plane.v = glm::normalize(m.points[3] - m.points[2]);
            m.plane.centre = 0.25 * (m.points[0] + m.points[1] + m.points[2] + m.points[3]);
        }
        m.text = group.comment.value_or(std::string());
        readStatistics(m, statistics, name, out.notShown);
        out.measurement = std::move(m);
    }
    for (const std::string& item : group.otherItems) {
        out.notShown.push_back(name + ": " + item);
    }
    if (group.geometry && !out.measurement) {
        out.notShown.push_back(name + ": Lucent geometry that could not be read");
    }
    return out;
}

} // namespace lucent
