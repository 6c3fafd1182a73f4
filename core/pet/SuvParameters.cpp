#include "core/pet/SuvParameters.h"

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

namespace lucent {

namespace {

std::optional<int> digits(std::string_view s) {
    int v = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || ptr != s.data() + s.size() || v < 0) {
        return std::nullopt;
    }
    return v;
}

std::string without(std::string_view s, char c) {
    std::string out;
    for (const char ch : s) {
        if (ch != c && ch != ' ') {
            out += ch;
        }
    }
    return out;
}

// Days since 1970-01-01 of a DA value.
std::optional<double> dateDays(std::string_view da) {
    const std::string d = without(da, '.');
    const auto y = digits(std::string_view(d).substr(0, 4));
    const auto m = d.size() == 8 ? digits(std::string_view(d).substr(4, 2)) : std::nullopt;
    const auto day = d.size() == 8 ? digits(std::string_view(d).substr(6, 2)) : std::nullopt;
    if (!y || !m || !day) {
        return std::nullopt;
    }
    using namespace std::chrono;
    const year_month_day ymd{year{*y}, month{static_cast<unsigned>(*m)},
                             std::chrono::day{static_cast<unsigned>(*day)}};
    if (!ymd.ok()) {
        return std::nullopt;
    }
    return static_cast<double>(sys_days(ymd).time_since_epoch().count());
}

// Seconds since midnight of a TM value.
std::optional<double> timeSeconds(std::string_view tm) {
    const std::string t = without(tm, ':');
    const std::size_t dot = t.find('.');
    const std::string_view whole = std::string_view(t).substr(0, dot);
    if (whole.size() != 2 && whole.size() != 4 && whole.size() != 6) {
        return std::nullopt;
    }
    int parts[3] = {0, 0, 0};
    for (std::size_t n = 0; n * 2 < whole.size(); ++n) {
        const auto v = digits(whole.substr(n * 2, 2));
        if (!v) {
            return std::nullopt;
        }
        parts[n] = *v;
    }
    if (parts[0] > 23 || parts[1] > 59 || parts[2] > 60) {
        return std::nullopt;
    }
    double fraction = 0.0;
    if (dot != std::string::npos) {
        const std::string_view f = std::string_view(t).substr(dot + 1);
        if (!f.empty() && (f.size() > 6 || !digits(f))) {
            return std::nullopt;
        }
        fraction = f.empty() ? 0.0 : *digits(f) / std::pow(10.0, static_cast<double>(f.size()));
    }
    return parts[0] * 3600.0 + parts[1] * 60.0 + parts[2] + fraction;
}

bool hasValue(std::string_view multiValue, std::string_view word) {
    std::size_t start = 0;
    while (start <= multiValue.size()) {
        const std::size_t end = multiValue.find('\\', start);
        std::string_view part = multiValue.substr(start, end - start);
        while (!part.empty() && part.front() == ' ') {
            part.remove_prefix(1);
        }
        while (!part.empty() && part.back() == ' ') {
            part.remove_suffix(1);
        }
        if (part == word) {
            return true;
        }
        if (end == std::string_view::npos) {
            break;
        }
        start = end + 1;
    }
    return false;
}

std::string number(double v) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

struct ScanReference {
    double time = 0.0;
    const char* name = "";
};

ScanReference scanReference(const SuvParameters& p) {
    const auto& series = p.seriesTime;
    const auto& acquisition = p.earliestAcquisitionTime;
    if (series && (!acquisition || *series <= *acquisition)) {
        return {*series, "SeriesDate/SeriesTime (0008,0021/0031)"};
    }
    if (acquisition) {
        return {*acquisition, "the earliest AcquisitionDate/AcquisitionTime (0008,0022/0032)"};
    }
    throw SuvError("SeriesDate/SeriesTime (0008,0021/0031) and AcquisitionDate/AcquisitionTime "
                   "(0008,0022/0032) are missing or not valid: no scan time to decay to");
}

void checkUnits(const SuvParameters& p) {
    if (p.units == "BQML") {
        return;
    }
    const std::string head = "Units (0054,1001) is ";
    if (p.units.empty()) {
        throw SuvError("Units (0054,1001) is missing: the values' unit is unknown");
    }
    if (p.units == "CNTS") {
        throw SuvError(head + "CNTS: counts have no calibration to Bq/mL (a vendor's factor, "
                              "such as Philips (7053,1009), is not read)");
    }
    if (p.units == "GML") {
        throw SuvError(head + "GML: the values are already SUVbw (g/mL); there is no factor "
                              "from Bq/mL to compute");
    }
    throw SuvError(head + p.units + ": only BQML (Bq/mL) values can be turned into SUVbw");
}

void checkCorrections(const SuvParameters& p) {
    if (p.correctedImage.empty()) {
        throw SuvError("CorrectedImage (0028,0051) is missing: it must list ATTN and DECY");
    }
    if (!hasValue(p.correctedImage, "ATTN")) {
        throw SuvError("CorrectedImage (0028,0051) is " + p.correctedImage +
                       ": it lacks ATTN (the values are not attenuation corrected)");
    }
    if (!hasValue(p.correctedImage, "DECY")) {
        throw SuvError("CorrectedImage (0028,0051) is " + p.correctedImage +
                       ": it lacks DECY (the values are not decay corrected)");
    }
    if (p.decayCorrection != "START") {
        throw SuvError("DecayCorrection (0054,1102) is " +
                       (p.decayCorrection.empty() ? std::string("missing") : p.decayCorrection) +
                       ": only START (decay corrected to the series start) is handled");
    }
}

double positive(const std::optional<double>& v, const std::string& element,
                const std::string& where = {}) {
    if (!v) {
        throw SuvError(element + " is missing" + where);
    }
    if (!(*v > 0.0) || !std::isfinite(*v)) {
        throw SuvError(element + " is " + number(*v) + where + ": it must be positive");
    }
    return *v;
}

} // namespace

std::optional<double> dicomDateTimeSeconds(std::string_view da, std::string_view tm) {
    const auto days = dateDays(da);
    const auto seconds = timeSeconds(tm);
    if (!days || !seconds) {
        return std::nullopt;
    }
    return *days * 86400.0 + *seconds;
}

std::optional<double> dicomDtSeconds(std::string_view dt) {
    const std::size_t zone = dt.find_first_of("+-");
    const std::string_view local = dt.substr(0, zone);
    if (local.size() < 8) {
        return std::nullopt;
    }
    const std::string_view time = local.substr(8);
    return dicomDateTimeSeconds(local.substr(0, 8), time.empty() ? "00" : time);
}

double suvScanReferenceTime(const SuvParameters& p) {
    return scanReference(p).time;
}

double suvBwFactor(const SuvParameters& p) {
    checkUnits(p);
    checkCorrections(p);
    const double weightKg = positive(p.patientWeightKg, "PatientWeight (0010,1030)");
    const std::string sequence = " (in RadiopharmaceuticalInformationSequence (0054,0016))";
    const double dose = positive(p.totalDoseBq, "RadionuclideTotalDose (0018,1074)", sequence);
    const double halfLife = positive(p.halfLifeS, "RadionuclideHalfLife (0018,1075)", sequence);
    if (!p.injectionTime) {
        throw SuvError("RadiopharmaceuticalStartDateTime (0018,1078) and "
                       "RadiopharmaceuticalStartTime (0018,1072) are missing or not valid" +
                       sequence);
    }
    const ScanReference scan = scanReference(p);
    const double dt = scan.time - *p.injectionTime;
    if (dt < 0.0) {
        throw SuvError("RadiopharmaceuticalStartTime/StartDateTime (0018,1072/1078) is " +
                       number(-dt) + " s after the scan reference, " + scan.name +
                       ": the decay time would be negative");
    }
    return weightKg * 1000.0 / (dose * std::exp2(-dt / halfLife));
}

} // namespace lucent
