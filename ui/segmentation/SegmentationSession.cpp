#include "ui/segmentation/SegmentationSession.h"

namespace lucent {

SegmentationSession::SegmentationSession(std::shared_ptr<const Volume> volume, QObject* parent)
    : QObject(parent), volume_(std::move(volume)), segmentation_(volume_->geometry()) {}

bool SegmentationSession::setVolume(std::shared_ptr<const Volume> volume) {
    if (!volume || volume->dims() != segmentation_.geometry().dims) {
        return false;
    }
    volume_ = std::move(volume);
    return true;
}

void SegmentationSession::notifyChanged() {
    if (segmentation_.find(active_) == nullptr) {
        setActiveSegment(segmentation_.segments().empty() ? 0 : segmentation_.segments().back().id);
    }
    emit segmentsChanged();
}

bool SegmentationSession::changed(bool edited) {
    if (edited) {
        notifyChanged();
    }
    return edited;
}

void SegmentationSession::setActiveSegment(std::uint32_t id) {
    if (id != 0 && segmentation_.find(id) == nullptr) {
        return;
    }
    if (id != active_) {
        active_ = id;
        emit activeSegmentChanged(id);
    }
}

std::uint32_t SegmentationSession::addSegment(const QString& name, const SegmentKind* kind) {
    QString named = name;
    for (int n = static_cast<int>(segmentation_.segments().size()) + 1; named.isEmpty(); ++n) {
        const std::string candidate = "Segment " + std::to_string(n);
        bool taken = false;
        for (const Segment& s : segmentation_.segments()) {
            taken = taken || s.name == candidate;
        }
        if (!taken) {
            named = QString::fromStdString(candidate);
        }
    }
    SegmentKind plain = *findSegmentKind("tissue");
    if (kind == nullptr) {
        // Distinct colours for plain segments (Slicer's generic anatomy colours' first few).
        static constexpr std::array<unsigned, 8> kColours{0x80AE80, 0xF1D691, 0xB17A65, 0x6FB8D2,
                                                          0xD8654F, 0xDD8265, 0x90EE90, 0xC06858};
        plain.colour = kColours[segmentation_.segments().size() % kColours.size()];
    }
    const std::uint32_t id =
        segmentation_.add(named.toStdString(), kind != nullptr ? kind : &plain);
    setActiveSegment(id);
    emit segmentsChanged();
    return id;
}

bool SegmentationSession::removeSegment(std::uint32_t id) {
    return changed(segmentation_.remove(id));
}

bool SegmentationSession::rename(std::uint32_t id, const QString& name) {
    return changed(segmentation_.rename(id, name.toStdString()));
}

bool SegmentationSession::setColour(std::uint32_t id, const std::array<std::uint8_t, 3>& colour) {
    return changed(segmentation_.setColour(id, colour));
}

bool SegmentationSession::setKind(std::uint32_t id, const SegmentKind& kind) {
    return changed(segmentation_.setKind(id, kind));
}

bool SegmentationSession::setVisible(std::uint32_t id, bool visible) {
    return changed(segmentation_.setVisible(id, visible));
}

bool SegmentationSession::setLocked(std::uint32_t id, bool locked) {
    return changed(segmentation_.setLocked(id, locked));
}

bool SegmentationSession::apply(std::uint32_t id, SegmentMask mask, const QString& what,
                                const std::string& algorithm) {
    return changed(segmentation_.setMask(id, std::move(mask), what.toStdString(), algorithm));
}

bool SegmentationSession::undo() {
    return changed(segmentation_.undo());
}

bool SegmentationSession::redo() {
    return changed(segmentation_.redo());
}

void SegmentationSession::setPreview(std::optional<Preview> preview) {
    if (!preview && !preview_) {
        return;
    }
    preview_ = std::move(preview);
    emit previewChanged();
}

SegmentationSessions::SegmentationSessions(QObject* parent) : QObject(parent) {}

std::string SegmentationSessions::keyOf(const Volume& volume) const {
    return volume.seriesUid.empty()
               ? "volume:" + std::to_string(reinterpret_cast<std::uintptr_t>(&volume))
               : volume.seriesUid;
}

SegmentationSession* SegmentationSessions::sessionFor(const std::shared_ptr<const Volume>& volume) {
    if (!volume || volume->empty()) {
        return nullptr;
    }
    const std::string key = keyOf(*volume);
    if (const auto known = sessions_.find(key); known != sessions_.end()) {
        known->second->setVolume(volume);
        return known->second;
    }
    auto* made = new SegmentationSession(volume, this);
    sessions_[key] = made;
    emit sessionOpened(made);
    return made;
}

SegmentationSession* SegmentationSessions::find(const Volume& volume) const {
    const auto known = sessions_.find(keyOf(volume));
    return known == sessions_.end() ? nullptr : known->second;
}

std::vector<SegmentationSession*> SegmentationSessions::sessions() const {
    std::vector<SegmentationSession*> out;
    for (const auto& [key, session] : sessions_) {
        out.push_back(session);
    }
    return out;
}

} // namespace lucent
