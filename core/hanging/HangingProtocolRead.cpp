// Reading hanging-protocol files: every error names the file and the key.
#include "core/hanging/HangingProtocolJson.h"
#include "core/hanging/HangingProtocolNames_p.h"
#include "core/mpr/WindowPresets.h"

#include <cctype>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include <nlohmann/json.hpp>

namespace lucent {

namespace {

using nlohmann::json;

constexpr int kMaxGrid = 4; // 1x1 up to 4x4

class Reader {
public:
    explicit Reader(std::string source) : source_(std::move(source)) {}

    [[noreturn]] void fail(const std::string& key, const std::string& message) const {
        throw HangingProtocolError(source_ + ": " + key + ": " + message);
    }

    void checkKeys(const json& object, const std::string& key,
                   std::initializer_list<const char*> known) const {
        if (!object.is_object()) {
            fail(key, std::string("expected an object, got ") + object.type_name());
        }
        for (const auto& item : object.items()) {
            bool found = false;
            std::string list;
            for (const char* k : known) {
                found = found || item.key() == k;
                list += (list.empty() ? "" : ", ") + std::string(k);
            }
            if (!found) {
                fail(join(key, item.key()), "unknown key; the known keys are " + list);
            }
        }
    }

    static std::string join(const std::string& key, const std::string& sub) {
        return key.empty() ? sub : key + "." + sub;
    }

    const json* find(const json& object, const char* name) const {
        const auto it = object.find(name);
        return it == object.end() ? nullptr : &*it;
    }

    std::string string(const json& object, const std::string& key, const char* name,
                       bool required = false) const {
        const json* v = find(object, name);
        if (v == nullptr) {
            if (required) {
                fail(join(key, name), "missing");
            }
            return {};
        }
        if (!v->is_string()) {
            fail(join(key, name), std::string("expected a string, got ") + v->type_name());
        }
        return v->get<std::string>();
    }

    double number(const json& value, const std::string& key) const {
        if (!value.is_number() || !std::isfinite(value.get<double>())) {
            fail(key, std::string("expected a number, got ") + value.type_name());
        }
        return value.get<double>();
    }

    int integer(const json& value, const std::string& key, int lo, int hi) const {
        if (!value.is_number_integer()) {
            fail(key, std::string("expected a whole number, got ") + value.type_name());
        }
        const auto n = value.get<long long>();
        if (n < lo || n > hi) {
            fail(key, std::to_string(n) + " is out of range [" + std::to_string(lo) + ", " +
                          std::to_string(hi) + "]");
        }
        return static_cast<int>(n);
    }

    bool boolean(const json& object, const std::string& key, const char* name) const {
        const json* v = find(object, name);
        if (v != nullptr && !v->is_boolean()) {
            fail(join(key, name), std::string("expected true or false, got ") + v->type_name());
        }
        return v != nullptr && v->get<bool>();
    }

    // A string or a list of strings.
    std::vector<std::string> strings(const json& object, const std::string& key,
                                     const char* name) const {
        const json* v = find(object, name);
        if (v == nullptr) {
            return {};
        }
        const std::string k = join(key, name);
        if (v->is_string()) {
            return {v->get<std::string>()};
        }
        if (!v->is_array()) {
            fail(k, std::string("expected a string or a list of strings, got ") + v->type_name());
        }
        std::vector<std::string> result;
        for (std::size_t n = 0; n < v->size(); ++n) {
            if (!(*v)[n].is_string()) {
                fail(k + "[" + std::to_string(n) + "]",
                     std::string("expected a string, got ") + (*v)[n].type_name());
            }
            result.push_back((*v)[n].get<std::string>());
        }
        return result;
    }

    // A string or list of names, each one of `names` (case-insensitive).
    template <typename Enum, std::size_t N>
    std::vector<Enum> enums(const json& object, const std::string& key, const char* name,
                            const std::array<NamedValue<Enum>, N>& names) const {
        std::vector<Enum> result;
        for (const std::string& text : strings(object, key, name)) {
            result.push_back(enumValue(text, join(key, name), names));
        }
        return result;
    }

    template <typename Enum, std::size_t N>
    Enum enumValue(const std::string& text, const std::string& key,
                   const std::array<NamedValue<Enum>, N>& names) const {
        if (const auto value = valueOf(text, names)) {
            return *value;
        }
        fail(key, "'" + text + "' is none of " + listOf(names));
    }

    std::string regex(const json& object, const std::string& key, const char* name) const {
        std::string pattern = string(object, key, name);
        if (!pattern.empty()) {
            try {
                std::regex(pattern, std::regex::ECMAScript | std::regex::icase);
            } catch (const std::regex_error& e) {
                fail(join(key, name), "bad regular expression '" + pattern + "': " + e.what());
            }
        }
        return pattern;
    }

    // mustMatch and weights, of the criteria this rule may use.
    void scoring(const json& object, const std::string& key, CriterionScoring& scoring,
                 const std::vector<Criterion>& allowed) const {
        std::string list;
        for (Criterion c : allowed) {
            list += (list.empty() ? "" : ", ") + std::string(criterionName(c));
        }
        const auto criterion = [&](const std::string& text, const std::string& k) {
            for (Criterion c : allowed) {
                if (text == criterionName(c)) {
                    return static_cast<int>(c);
                }
            }
            fail(k, "'" + text + "' is none of " + list);
        };
        const std::string mustKey = join(key, "mustMatch");
        for (const std::string& text : strings(object, key, "mustMatch")) {
            scoring.mustMatch[criterion(text, mustKey)] = true;
        }
        if (const json* w = find(object, "weights")) {
            const std::string wKey = join(key, "weights");
            if (!w->is_object()) {
                fail(wKey, std::string("expected an object, got ") + w->type_name());
            }
            for (const auto& item : w->items()) {
                const std::string k = join(wKey, item.key());
                scoring.weight[criterion(item.key(), k)] = number(item.value(), k);
            }
        }
    }

    template <typename T>
    void range(const json& object, const std::string& key, const char* name, std::optional<T>& lo,
               std::optional<T>& hi) const {
        const json* v = find(object, name);
        if (v == nullptr) {
            return;
        }
        const std::string k = join(key, name);
        checkKeys(*v, k, {"min", "max"});
        const auto read = [&](const char* bound, std::optional<T>& out) {
            if (const json* b = find(*v, bound)) {
                if constexpr (std::is_same_v<T, int>) {
                    out = integer(*b, join(k, bound), 0, 1 << 30);
                } else {
                    out = number(*b, join(k, bound));
                }
            }
        };
        read("min", lo);
        read("max", hi);
        if (!lo && !hi) {
            fail(k, "give min, max or both");
        }
        if (lo && hi && *lo > *hi) {
            fail(k, "min is above max");
        }
    }

    StudyRule study(const json& object, const std::string& key) const {
        checkKeys(object, key, {"modality", "bodyPart", "description", "mustMatch", "weights"});
        StudyRule rule;
        rule.modalities = strings(object, key, "modality");
        rule.bodyPart = regex(object, key, "bodyPart");
        rule.description = regex(object, key, "description");
        scoring(object, key, rule.scoring,
                {Criterion::Modality, Criterion::BodyPart, Criterion::Description});
        return rule;
    }

    SeriesRule series(const json& object, const std::string& key) const {
        checkKeys(object, key,
                  {"name", "studyOrder", "modality", "bodyPart", "description", "sliceThickness",
                   "orientation", "instances", "kind", "mustMatch", "weights", "required",
                   "fallback"});
        SeriesRule rule;
        rule.name = string(object, key, "name", true);
        if (rule.name.empty()) {
            fail(join(key, "name"), "empty");
        }
        if (const json* order = find(object, "studyOrder")) {
            rule.studyOrder = order->is_string() && order->get<std::string>() == "any"
                                  ? kAnyStudy
                                  : integer(*order, join(key, "studyOrder"), 0, 99);
        }
        rule.modalities = strings(object, key, "modality");
        rule.bodyPart = regex(object, key, "bodyPart");
        rule.description = regex(object, key, "description");
        range(object, key, "sliceThickness", rule.minSliceThickness, rule.maxSliceThickness);
        rule.orientations = enums(object, key, "orientation", kOrientationNames);
        range(object, key, "instances", rule.minInstances, rule.maxInstances);
        rule.kinds = enums(object, key, "kind", kKindNames);
        scoring(object, key, rule.scoring,
                {Criterion::Modality, Criterion::BodyPart, Criterion::Description,
                 Criterion::SliceThickness, Criterion::Orientation, Criterion::Instances,
                 Criterion::Kind});
        rule.required = boolean(object, key, "required");
        rule.fallback = string(object, key, "fallback");
        return rule;
    }

    ViewportSpec viewport(const json& object, const std::string& key) const {
        checkKeys(object, key,
                  {"series", "view", "window", "link", "row", "column", "rowSpan", "columnSpan"});
        ViewportSpec spec;
        spec.seriesSlot = string(object, key, "series", true);
        if (const json* view = find(object, "view")) {
            if (!view->is_string()) {
                fail(join(key, "view"), std::string("expected a string, got ") + view->type_name());
            }
            spec.view = enumValue(view->get<std::string>(), join(key, "view"), kViewNames);
        }
        const std::string window = string(object, key, "window");
        if (!window.empty()) {
            spec.windowPreset = windowPresetName(window, join(key, "window"));
        }
        if (const json* link = find(object, "link")) {
            spec.linkGroup = integer(*link, join(key, "link"), 0, 99);
        }
        return spec;
    }

    // The preset's name as core/mpr lists it, found case-insensitively.
    std::string windowPresetName(const std::string& text, const std::string& key) const {
        std::string list;
        for (const WindowPreset& preset : windowPresets()) {
            if (equalNoCase(preset.name, text)) {
                return std::string(preset.name);
            }
            list += (list.empty() ? "" : ", ") + std::string(preset.name);
        }
        fail(key, "unknown window preset '" + text + "'; the presets are " + list);
    }

    // Cells: all explicit, or none (then filled in order: row by row, or the
    // asymmetric layouts' big cell first).
    void cells(const json& list, const std::string& key, const std::string& layout,
               ViewportSet& set) const;

    ViewportSet viewportSet(const json& object, const std::string& key) const;

    HangingProtocol protocol(const json& root) const;

private:
    std::string source_;
};

void Reader::cells(const json& list, const std::string& key, const std::string& layout,
                   ViewportSet& set) const {
    const auto given = [&](const json& v) { return v.contains("row") || v.contains("column"); };
    const bool explicitCells = std::any_of(list.begin(), list.end(), given);
    for (std::size_t n = 0; n < list.size(); ++n) {
        ViewportSpec& spec = set.viewports[n];
        const std::string k = key + "[" + std::to_string(n) + "]";
        if (explicitCells) {
            if (!list[n].contains("row") || !list[n].contains("column")) {
                fail(k, "give row and column of every viewport, or of none");
            }
            spec.row = integer(list[n]["row"], k + ".row", 0, set.rows - 1);
            spec.column = integer(list[n]["column"], k + ".column", 0, set.columns - 1);
            if (list[n].contains("rowSpan")) {
                spec.rowSpan = integer(list[n]["rowSpan"], k + ".rowSpan", 1, set.rows - spec.row);
            }
            if (list[n].contains("columnSpan")) {
                spec.columnSpan =
                    integer(list[n]["columnSpan"], k + ".columnSpan", 1, set.columns - spec.column);
            }
        } else if (list[n].contains("rowSpan") || list[n].contains("columnSpan")) {
            fail(k, "a span needs row and column");
        } else if (layout == "1+2") {
            constexpr int kCells[3][3] = {{0, 0, 2}, {0, 1, 1}, {1, 1, 1}}; // row, column, rowSpan
            spec.row = kCells[n][0], spec.column = kCells[n][1], spec.rowSpan = kCells[n][2];
        } else if (layout == "2+1") {
            constexpr int kCells[3][3] = {{0, 0, 1}, {1, 0, 1}, {0, 1, 2}};
            spec.row = kCells[n][0], spec.column = kCells[n][1], spec.rowSpan = kCells[n][2];
        } else {
            spec.row = static_cast<int>(n) / set.columns;
            spec.column = static_cast<int>(n) % set.columns;
        }
    }
    std::vector<int> owner(static_cast<std::size_t>(set.rows * set.columns), -1);
    for (std::size_t n = 0; n < set.viewports.size(); ++n) {
        const ViewportSpec& s = set.viewports[n];
        for (int r = s.row; r < s.row + s.rowSpan; ++r) {
            for (int c = s.column; c < s.column + s.columnSpan; ++c) {
                int& cell = owner[static_cast<std::size_t>(r * set.columns + c)];
                if (cell >= 0) {
                    fail(key + "[" + std::to_string(n) + "]",
                         "overlaps viewport " + std::to_string(cell) + " at row " +
                             std::to_string(r) + ", column " + std::to_string(c));
                }
                cell = static_cast<int>(n);
            }
        }
    }
}

ViewportSet Reader::viewportSet(const json& object, const std::string& key) const {
    checkKeys(object, key, {"name", "layout", "rows", "columns", "viewports"});
    ViewportSet set;
    set.name = string(object, key, "name");
    const std::string layout = string(object, key, "layout");
    const bool rowsGiven = object.contains("rows") || object.contains("columns");
    if (layout.empty() == !rowsGiven) {
        fail(key, "give either layout (\"2x2\", \"1+2\", \"2+1\") or rows and columns");
    }
    std::size_t capacity = 0;
    if (rowsGiven) {
        if (!object.contains("rows") || !object.contains("columns")) {
            fail(key, "give both rows and columns");
        }
        set.rows = integer(object["rows"], join(key, "rows"), 1, kMaxGrid);
        set.columns = integer(object["columns"], join(key, "columns"), 1, kMaxGrid);
    } else if (layout == "1+2" || layout == "2+1") {
        set.rows = set.columns = 2;
        capacity = 3;
    } else {
        const std::regex grid("([1-4])x([1-4])");
        std::smatch m;
        if (!std::regex_match(layout, m, grid)) {
            fail(join(key, "layout"), "'" + layout + "' is none of RxC (1 to 4 each), 1+2, 2+1");
        }
        set.rows = std::stoi(m[1]);
        set.columns = std::stoi(m[2]);
    }
    capacity = capacity ? capacity : static_cast<std::size_t>(set.rows * set.columns);
    const json* list = find(object, "viewports");
    const std::string listKey = join(key, "viewports");
    if (list == nullptr || !list->is_array() || list->empty()) {
        fail(listKey, "expected a non-empty list of viewports");
    }
    if (list->size() > capacity) {
        fail(listKey,
             std::to_string(list->size()) + " viewports do not fit a " +
                 (layout.empty() ? std::to_string(set.rows) + "x" + std::to_string(set.columns)
                                 : layout) +
                 " grid");
    }
    for (std::size_t n = 0; n < list->size(); ++n) {
        set.viewports.push_back(viewport((*list)[n], listKey + "[" + std::to_string(n) + "]"));
    }
    cells(*list, listKey, layout, set);
    return set;
}

HangingProtocol Reader::protocol(const json& root) const {
    checkKeys(root, "", {"name", "description", "priority", "study", "series", "viewportSets"});
    HangingProtocol p;
    p.name = string(root, "", "name", true);
    if (p.name.empty()) {
        fail("name", "empty");
    }
    p.description = string(root, "", "description");
    if (const json* priority = find(root, "priority")) {
        p.priority = number(*priority, "priority");
    }
    if (const json* study = find(root, "study")) {
        p.study = this->study(*study, "study");
    }
    const json* slots = find(root, "series");
    if (slots == nullptr || !slots->is_array() || slots->empty()) {
        fail("series", "expected a non-empty list of series slots");
    }
    for (std::size_t n = 0; n < slots->size(); ++n) {
        const std::string key = "series[" + std::to_string(n) + "]";
        SeriesRule rule = series((*slots)[n], key);
        if (p.slot(rule.name)) {
            fail(key + ".name", "'" + rule.name + "' is used twice");
        }
        p.seriesSlots.push_back(std::move(rule));
    }
    for (std::size_t n = 0; n < p.seriesSlots.size(); ++n) {
        const std::string& fallback = p.seriesSlots[n].fallback;
        if (!fallback.empty() && (fallback == p.seriesSlots[n].name || !p.slot(fallback))) {
            fail("series[" + std::to_string(n) + "].fallback",
                 "'" + fallback + "' is no other slot of this protocol");
        }
    }
    const json* sets = find(root, "viewportSets");
    if (sets == nullptr || !sets->is_array() || sets->empty()) {
        fail("viewportSets", "expected a non-empty list of viewport sets");
    }
    for (std::size_t n = 0; n < sets->size(); ++n) {
        const std::string key = "viewportSets[" + std::to_string(n) + "]";
        p.viewportSets.push_back(viewportSet((*sets)[n], key));
        const std::vector<ViewportSpec>& viewports = p.viewportSets.back().viewports;
        for (std::size_t v = 0; v < viewports.size(); ++v) {
            if (!p.slot(viewports[v].seriesSlot)) {
                fail(key + ".viewports[" + std::to_string(v) + "].series",
                     "'" + viewports[v].seriesSlot + "' is no slot of this protocol");
            }
        }
    }
    return p;
}

} // namespace

HangingProtocol parseHangingProtocol(const std::string& text, const std::string& source) {
    json root;
    try {
        root = json::parse(text);
    } catch (const json::parse_error& e) {
        throw HangingProtocolError(source + ": not valid JSON: " + e.what());
    }
    HangingProtocol protocol = Reader(source).protocol(root);
    protocol.file = source;
    return protocol;
}

HangingProtocol readHangingProtocol(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        throw HangingProtocolError(file.string() + ": cannot be read");
    }
    std::ostringstream text;
    text << in.rdbuf();
    return parseHangingProtocol(text.str(), file.string());
}

} // namespace lucent
