#include "core/segmentation/Segmentation.h"

#include <algorithm>
#include <stdexcept>

namespace lucent {
namespace {

// Shown and locked are not edits: an undo or redo keeps them as they are now.
void keepDisplayFlags(std::vector<Segment>& restored, const std::vector<Segment>& now) {
    for (Segment& s : restored) {
        const auto it =
            std::find_if(now.begin(), now.end(), [&](const Segment& n) { return n.id == s.id; });
        if (it != now.end()) {
            s.visible = it->visible;
            s.locked = it->locked;
        }
    }
}

} // namespace

Segmentation::Segmentation(const VolumeGeometry& grid, std::size_t historySteps)
    : grid_(grid), history_(historySteps) {}

const Segment* Segmentation::find(std::uint32_t id) const {
    const auto it = std::find_if(segments_.begin(), segments_.end(),
                                 [id](const Segment& s) { return s.id == id; });
    return it == segments_.end() ? nullptr : &*it;
}

Segment* Segmentation::locate(std::uint32_t id) {
    const auto it = std::find_if(segments_.begin(), segments_.end(),
                                 [id](const Segment& s) { return s.id == id; });
    return it == segments_.end() ? nullptr : &*it;
}

void Segmentation::record(std::string what) {
    history_.record(std::move(what), segments_);
    ++revision_;
}

std::uint32_t Segmentation::add(const std::string& name, const SegmentKind* kind) {
    const SegmentKind& k = kind != nullptr ? *kind : *findSegmentKind("tissue");
    record("Add segment " + name);
    Segment s;
    s.id = nextId_++;
    s.name = name;
    s.colour = {static_cast<std::uint8_t>(k.colour >> 16), static_cast<std::uint8_t>(k.colour >> 8),
                static_cast<std::uint8_t>(k.colour)};
    s.category = k.category;
    s.type = k.type;
    s.mask = std::make_shared<const SegmentMask>(grid_.dims);
    segments_.push_back(std::move(s));
    return segments_.back().id;
}

bool Segmentation::remove(std::uint32_t id) {
    const Segment* s = find(id);
    if (s == nullptr) {
        return false;
    }
    record("Remove segment " + s->name);
    std::erase_if(segments_, [id](const Segment& x) { return x.id == id; });
    return true;
}

bool Segmentation::rename(std::uint32_t id, const std::string& name) {
    const Segment* s = find(id);
    if (s == nullptr || s->name == name) {
        return false;
    }
    record("Rename " + s->name + " to " + name);
    locate(id)->name = name;
    return true;
}

bool Segmentation::setColour(std::uint32_t id, const std::array<std::uint8_t, 3>& colour) {
    const Segment* s = find(id);
    if (s == nullptr || s->colour == colour) {
        return false;
    }
    record("Colour " + s->name);
    locate(id)->colour = colour;
    return true;
}

bool Segmentation::setKind(std::uint32_t id, const SegmentKind& kind) {
    const Segment* s = find(id);
    if (s == nullptr) {
        return false;
    }
    record("Code " + s->name + " as " + kind.type.meaning);
    Segment* m = locate(id);
    m->category = kind.category;
    m->type = kind.type;
    return true;
}

bool Segmentation::setVisible(std::uint32_t id, bool visible) {
    Segment* s = locate(id);
    if (s == nullptr) {
        return false;
    }
    s->visible = visible;
    return true;
}

bool Segmentation::setLocked(std::uint32_t id, bool locked) {
    Segment* s = locate(id);
    if (s == nullptr) {
        return false;
    }
    s->locked = locked;
    return true;
}

bool Segmentation::setMask(std::uint32_t id, SegmentMask mask, const std::string& what,
                           const std::string& algorithm, bool automatic) {
    std::vector<std::pair<std::uint32_t, SegmentMask>> one;
    one.emplace_back(id, std::move(mask));
    return setMasks(std::move(one), what, algorithm, automatic);
}

bool Segmentation::setMasks(std::vector<std::pair<std::uint32_t, SegmentMask>> masks,
                            const std::string& what, const std::string& algorithm, bool automatic) {
    for (const auto& [id, mask] : masks) {
        if (mask.dims() != grid_.dims) {
            throw std::invalid_argument("Segmentation: a mask of other dimensions than the series");
        }
        const Segment* s = find(id);
        if (s == nullptr || s->locked) {
            return false;
        }
    }
    if (masks.empty()) {
        return false;
    }
    record(what);
    for (auto& [id, mask] : masks) {
        Segment* m = locate(id);
        m->mask = std::make_shared<const SegmentMask>(std::move(mask));
        if (!algorithm.empty()) {
            m->algorithmType = automatic ? "AUTOMATIC" : "SEMIAUTOMATIC";
            m->algorithmName = algorithm;
        }
    }
    return true;
}

bool Segmentation::undo() {
    const std::vector<Segment> now = segments_;
    if (!history_.undo(segments_)) {
        return false;
    }
    keepDisplayFlags(segments_, now);
    ++revision_;
    return true;
}

bool Segmentation::redo() {
    const std::vector<Segment> now = segments_;
    if (!history_.redo(segments_)) {
        return false;
    }
    keepDisplayFlags(segments_, now);
    ++revision_;
    return true;
}

} // namespace lucent
