#include "core/followup/FollowUpText.h"

#include <algorithm>
#include <cstdio>

namespace lucent {

namespace {

std::string number(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f", v);
    return buffer;
}

std::string joined(const std::vector<std::string>& parts, const char* separator) {
    std::string out;
    for (const std::string& p : parts) {
        out += (out.empty() ? "" : separator) + p;
    }
    return out;
}

std::string csvField(const std::string& cell) {
    if (cell.find_first_of(",\"\r\n") == std::string::npos) {
        return cell;
    }
    std::string out = "\"";
    for (const char c : cell) {
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    }
    return out + "\"";
}

// Display columns of UTF-8 text: continuation bytes take none.
std::size_t columnsOf(const std::string& text) {
    return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
        return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
    }));
}

} // namespace

std::string formatPercent(const std::optional<double>& percent) {
    if (!percent) {
        return {};
    }
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%+.1f %%", *percent);
    return buffer;
}

std::string formatLesionCell(const LesionRow& row, const std::optional<LesionObservation>& o) {
    if (!o) {
        return {};
    }
    if (row.role != LesionRole::Target) {
        return "present";
    }
    return o->gone ? std::string("0 (gone)") : number(o->diameterMm);
}

std::string formatLesionRole(const LesionRow& row) {
    std::string role = lesionRoleName(row.role);
    if (row.lymphNode) {
        role += ", lymph node";
    }
    return role;
}

FollowUpGrid followUpGrid(const FollowUpTable& table) {
    FollowUpGrid grid;
    std::vector<std::string> header{"Lesion", "Role"};
    for (const TimepointAssessment& t : table.timepoints) {
        header.push_back(formatStudyDate(t.studyDate));
    }
    grid.rows.push_back(header);
    for (const LesionRow& lesion : table.lesions) {
        std::vector<std::string> row{lesion.name, formatLesionRole(lesion)};
        for (const std::optional<LesionObservation>& o : lesion.at) {
            row.push_back(formatLesionCell(lesion, o));
        }
        grid.rows.push_back(row);
    }
    std::vector<std::string> sum{"Sum of diameters (mm)", ""}, baseline{"Change from baseline", ""},
        nadir{"Change from nadir", ""}, response{"Response", ""}, reason{"Reason", ""};
    for (const TimepointAssessment& t : table.timepoints) {
        sum.push_back(number(t.sumMm) + (t.evaluable ? "" : " (incomplete)"));
        baseline.push_back(formatPercent(t.fromBaselinePercent));
        nadir.push_back(formatPercent(t.fromNadirPercent));
        response.push_back(recistResponseName(t.response));
        reason.push_back(joined(t.reasons, "; "));
    }
    for (auto* row : {&sum, &baseline, &nadir, &response, &reason}) {
        grid.rows.push_back(std::move(*row));
    }
    return grid;
}

std::string followUpCsv(const FollowUpTable& table) {
    std::string out;
    for (const std::vector<std::string>& row : followUpGrid(table).rows) {
        std::vector<std::string> fields;
        std::transform(row.begin(), row.end(), std::back_inserter(fields), csvField);
        out += joined(fields, ",") + "\r\n";
    }
    return out;
}

std::string followUpText(const FollowUpTable& table) {
    const FollowUpGrid grid = followUpGrid(table);
    std::vector<std::size_t> widths;
    for (const std::vector<std::string>& row : grid.rows) {
        widths.resize(std::max(widths.size(), row.size()));
        for (std::size_t c = 0; c < row.size(); ++c) {
            widths[c] = std::max(widths[c], columnsOf(row[c]));
        }
    }
    std::string out;
    for (const std::vector<std::string>& row : grid.rows) {
        std::string line;
        for (std::size_t c = 0; c < row.size(); ++c) {
            line += row[c] + std::string(widths[c] - columnsOf(row[c]) + 2, ' ');
        }
        line.erase(line.find_last_not_of(' ') + 1);
        out += line + "\n";
    }
    return out;
}

} // namespace lucent
