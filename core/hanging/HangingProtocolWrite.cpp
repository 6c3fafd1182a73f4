// Writing protocol files ("save the current layout as a protocol") and loading folders.
#include "core/hanging/HangingProtocolJson.h"
#include "core/hanging/HangingProtocolNames_p.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

namespace lucent {

namespace {

using nlohmann::ordered_json;

template <typename Enum, std::size_t N>
ordered_json names(const std::vector<Enum>& values, const std::array<NamedValue<Enum>, N>& table) {
    ordered_json list = ordered_json::array();
    for (Enum v : values) {
        list.push_back(std::string(nameOf(v, table)));
    }
    return list;
}

void putScoring(ordered_json& o, const CriterionScoring& scoring) {
    const CriterionScoring defaults;
    ordered_json must = ordered_json::array();
    ordered_json weights = ordered_json::object();
    for (int c = 0; c < kCriterionCount; ++c) {
        const char* name = criterionName(static_cast<Criterion>(c));
        if (scoring.mustMatch[c]) {
            must.push_back(name);
        }
        if (scoring.weight[c] != defaults.weight[c]) {
            weights[name] = scoring.weight[c];
        }
    }
    if (!must.empty()) {
        o["mustMatch"] = must;
    }
    if (!weights.empty()) {
        o["weights"] = weights;
    }
}

template <typename T>
void putRange(ordered_json& o, const char* key, const std::optional<T>& lo,
              const std::optional<T>& hi) {
    if (!lo && !hi) {
        return;
    }
    ordered_json r = ordered_json::object();
    if (lo) {
        r["min"] = *lo;
    }
    if (hi) {
        r["max"] = *hi;
    }
    o[key] = r;
}

void putText(ordered_json& o, const char* key, const std::string& text) {
    if (!text.empty()) {
        o[key] = text;
    }
}

ordered_json seriesJson(const SeriesRule& rule) {
    ordered_json o = ordered_json::object();
    o["name"] = rule.name;
    if (rule.studyOrder == kAnyStudy) {
        o["studyOrder"] = "any";
    } else {
        o["studyOrder"] = rule.studyOrder;
    }
    if (!rule.modalities.empty()) {
        o["modality"] = rule.modalities;
    }
    putText(o, "bodyPart", rule.bodyPart);
    putText(o, "description", rule.description);
    putRange(o, "sliceThickness", rule.minSliceThickness, rule.maxSliceThickness);
    if (!rule.orientations.empty()) {
        o["orientation"] = names(rule.orientations, kOrientationNames);
    }
    putRange(o, "instances", rule.minInstances, rule.maxInstances);
    if (!rule.kinds.empty()) {
        o["kind"] = names(rule.kinds, kKindNames);
    }
    putScoring(o, rule.scoring);
    if (rule.required) {
        o["required"] = true;
    }
    putText(o, "fallback", rule.fallback);
    return o;
}

ordered_json setJson(const ViewportSet& set) {
    ordered_json o = ordered_json::object();
    o["name"] = set.name;
    o["rows"] = set.rows;
    o["columns"] = set.columns;
    ordered_json viewports = ordered_json::array();
    for (const ViewportSpec& v : set.viewports) {
        ordered_json j = ordered_json::object();
        j["series"] = v.seriesSlot;
        j["view"] = std::string(nameOf(v.view, kViewNames));
        putText(j, "window", v.windowPreset);
        if (v.linkGroup != 0) {
            j["link"] = v.linkGroup;
        }
        j["row"] = v.row;
        j["column"] = v.column;
        if (v.rowSpan != 1) {
            j["rowSpan"] = v.rowSpan;
        }
        if (v.columnSpan != 1) {
            j["columnSpan"] = v.columnSpan;
        }
        viewports.push_back(j);
    }
    o["viewports"] = viewports;
    return o;
}

std::string protocolText(const HangingProtocol& p) {
    ordered_json o = ordered_json::object();
    o["name"] = p.name;
    putText(o, "description", p.description);
    if (p.priority != 0) {
        o["priority"] = p.priority;
    }
    ordered_json study = ordered_json::object();
    if (!p.study.modalities.empty()) {
        study["modality"] = p.study.modalities;
    }
    putText(study, "bodyPart", p.study.bodyPart);
    putText(study, "description", p.study.description);
    putScoring(study, p.study.scoring);
    if (!study.empty()) {
        o["study"] = study;
    }
    o["series"] = ordered_json::array();
    for (const SeriesRule& rule : p.seriesSlots) {
        o["series"].push_back(seriesJson(rule));
    }
    o["viewportSets"] = ordered_json::array();
    for (const ViewportSet& set : p.viewportSets) {
        o["viewportSets"].push_back(setJson(set));
    }
    return o.dump(2) + "\n";
}

} // namespace

void writeHangingProtocol(const std::filesystem::path& file, const HangingProtocol& protocol) {
    // What is written must read back: the reader's checks are the writer's.
    const std::string text = protocolText(protocol);
    parseHangingProtocol(text, file.string());
    std::filesystem::path temporary = file;
    temporary += ".tmp";
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        if (!out) {
            throw HangingProtocolError(file.string() + ": cannot write: " + std::strerror(errno));
        }
        out << text;
        out.flush();
        if (!out) {
            std::error_code ignored;
            std::filesystem::remove(temporary, ignored);
            throw HangingProtocolError(file.string() + ": write error");
        }
    }
    std::error_code error;
    std::filesystem::rename(temporary, file, error);
    if (error) {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw HangingProtocolError(file.string() + ": cannot replace: " + error.message());
    }
}

std::vector<HangingProtocol> loadHangingProtocols(const std::vector<std::filesystem::path>& folders,
                                                  std::vector<std::string>* errors) {
    std::vector<HangingProtocol> result;
    std::set<std::string> earlier; // names of earlier folders
    for (const std::filesystem::path& folder : folders) {
        std::error_code error;
        std::vector<std::filesystem::path> files;
        for (std::filesystem::directory_iterator it(folder, error), end; !error && it != end;
             it.increment(error)) {
            if (it->path().extension() == ".json" && it->is_regular_file(error)) {
                files.push_back(it->path());
            }
        }
        std::sort(files.begin(), files.end());
        std::map<std::string, std::string> here; // name -> file, in this folder
        for (const std::filesystem::path& file : files) {
            try {
                HangingProtocol p = readHangingProtocol(file);
                if (const auto it = here.find(p.name); it != here.end()) {
                    throw HangingProtocolError(file.string() + ": name: '" + p.name +
                                               "' is already the name of " + it->second);
                }
                here.emplace(p.name, file.string());
                if (!earlier.count(p.name)) {
                    result.push_back(std::move(p));
                }
            } catch (const HangingProtocolError& e) {
                if (errors) {
                    errors->push_back(e.what());
                }
            }
        }
        for (const auto& [name, file] : here) {
            earlier.insert(name);
        }
    }
    return result;
}

std::string hangingProtocolFileName(const std::string& name) {
    std::string stem;
    for (char c : name) {
        const auto u = static_cast<unsigned char>(c);
        if (std::isalnum(u)) {
            stem += static_cast<char>(std::tolower(u));
        } else if (!stem.empty() && stem.back() != '-') {
            stem += '-';
        }
    }
    while (!stem.empty() && stem.back() == '-') {
        stem.pop_back();
    }
    return (stem.empty() ? "protocol" : stem) + ".json";
}

} // namespace lucent
