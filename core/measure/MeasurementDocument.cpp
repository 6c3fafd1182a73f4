#include "core/measure/MeasurementDocument.h"

#include <algorithm>
#include <cctype>
#include <set>

namespace lucent {

namespace {

std::string lowerName(MeasurementKind kind) {
    std::string name = measurementKindName(kind);
    std::transform(name.begin(), name.end(), name.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return name;
}

} // namespace

const Measurement* MeasurementDocument::find(std::uint64_t id) const {
    const auto it = std::find_if(measurements_.begin(), measurements_.end(),
                                 [id](const Measurement& m) { return m.id == id; });
    return it == measurements_.end() ? nullptr : &*it;
}

std::vector<Measurement>::iterator MeasurementDocument::locate(std::uint64_t id) {
    return std::find_if(measurements_.begin(), measurements_.end(),
                        [id](const Measurement& m) { return m.id == id; });
}

void MeasurementDocument::record(std::string what) {
    history_.record(std::move(what), measurements_);
    ++revision_;
}

std::uint64_t MeasurementDocument::add(Measurement m) {
    record("Add " + lowerName(m.kind));
    m.id = nextId_++;
    measurements_.push_back(std::move(m));
    return measurements_.back().id;
}

bool MeasurementDocument::change(const Measurement& m) {
    const auto it = locate(m.id);
    if (it == measurements_.end() || it->readOnly) {
        return false;
    }
    record("Change " + lowerName(m.kind));
    *locate(m.id) = m;
    return true;
}

bool MeasurementDocument::rename(std::uint64_t id, const std::string& label) {
    const auto it = locate(id);
    if (it == measurements_.end() || it->readOnly || it->label == label) {
        return false;
    }
    record("Rename " + lowerName(it->kind));
    locate(id)->label = label;
    return true;
}

bool MeasurementDocument::remove(std::uint64_t id) {
    const auto it = locate(id);
    if (it == measurements_.end() || it->readOnly) {
        return false;
    }
    record("Delete " + lowerName(it->kind));
    measurements_.erase(locate(id));
    return true;
}

void MeasurementDocument::clear() {
    const bool anyEditable = std::any_of(measurements_.begin(), measurements_.end(),
                                         [](const Measurement& m) { return !m.readOnly; });
    if (!anyEditable) {
        return;
    }
    record("Clear measurements");
    std::erase_if(measurements_, [](const Measurement& m) { return !m.readOnly; });
}

bool MeasurementDocument::undo() {
    if (!history_.undo(measurements_)) {
        return false;
    }
    ++revision_;
    return true;
}

bool MeasurementDocument::redo() {
    if (!history_.redo(measurements_)) {
        return false;
    }
    ++revision_;
    return true;
}

void MeasurementDocument::load(std::vector<Measurement> measurements) {
    std::set<std::uint64_t> seen;
    for (const Measurement& m : measurements) {
        nextId_ = std::max(nextId_, m.id + 1);
    }
    for (Measurement& m : measurements) {
        if (m.id == 0 || !seen.insert(m.id).second) {
            m.id = nextId_++;
            seen.insert(m.id);
        }
    }
    measurements_ = std::move(measurements);
    history_.clear();
    ++revision_;
}

} // namespace lucent
