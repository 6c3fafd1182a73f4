#pragma once
// The segments of each open series (a lucent::Segmentation, created on first use) and the
// segment the Segment Editor's effects act on: shared by every view that shows the series,
// the Segments panel, and whoever saves them (the SEG autosave listens to segmentsChanged
// and reads segmentation().revision()).

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <QObject>
#include <QString>

#include "core/segmentation/Segmentation.h"

namespace lucent {

class SegmentationSession : public QObject {
    Q_OBJECT

public:
    SegmentationSession(std::shared_ptr<const Volume> volume, QObject* parent = nullptr);

    // The series' voxels (thresholds and statistics read them) and its grid.
    const std::shared_ptr<const Volume>& volume() const { return volume_; }
    // The same series loaded again (the same grid; a different one is ignored: false).
    bool setVolume(std::shared_ptr<const Volume> volume);
    const Segmentation& segmentation() const { return segmentation_; }
    // For code that edits it directly (grow from seeds, scissors, a SEG read): call
    // notifyChanged() afterwards so the views and the panel follow.
    Segmentation& segmentation() { return segmentation_; }
    void notifyChanged();

    // The segment the effects change; 0 for none.
    std::uint32_t activeSegment() const { return active_; }
    const Segment* active() const { return segmentation_.find(active_); }
    void setActiveSegment(std::uint32_t id);

    // Each edit is one undo step of the segmentation, and emits segmentsChanged.
    // A new empty segment ("Segment n" when the name is empty), which becomes the active one.
    std::uint32_t addSegment(const QString& name = {}, const SegmentKind* kind = nullptr);
    bool removeSegment(std::uint32_t id);
    bool rename(std::uint32_t id, const QString& name);
    bool setColour(std::uint32_t id, const std::array<std::uint8_t, 3>& colour);
    bool setKind(std::uint32_t id, const SegmentKind& kind);
    // Not undo steps: what is shown and what effects may change.
    bool setVisible(std::uint32_t id, bool visible);
    bool setLocked(std::uint32_t id, bool locked);
    // An effect's result; false (nothing changes) for an unknown or locked segment.
    bool apply(std::uint32_t id, SegmentMask mask, const QString& what,
               const std::string& algorithm = {});
    bool undo();
    bool redo();

    // What a segment would become, drawn in the views in place of its voxels: a stroke
    // being painted, the threshold's range. touchPreview() after changing its mask in place.
    struct Preview {
        std::uint32_t segment = 0;
        std::shared_ptr<const SegmentMask> mask;
    };
    const std::optional<Preview>& preview() const { return preview_; }
    void setPreview(std::optional<Preview> preview);
    void touchPreview() { emit previewChanged(); }

signals:
    // Segments added, removed, renamed, recoloured, recoded, shown, hidden, locked or their
    // voxels changed (an edit, an undo, a redo).
    void segmentsChanged();
    void activeSegmentChanged(std::uint32_t id);
    void previewChanged();

private:
    bool changed(bool edited);

    std::shared_ptr<const Volume> volume_;
    Segmentation segmentation_;
    std::uint32_t active_ = 0;
    std::optional<Preview> preview_;
};

// One SegmentationSession per series (by series UID; a volume without one gets its own).
class SegmentationSessions : public QObject {
    Q_OBJECT

public:
    explicit SegmentationSessions(QObject* parent = nullptr);

    // The series' session, made (with no segment) on first use; nullptr for no volume.
    SegmentationSession* sessionFor(const std::shared_ptr<const Volume>& volume);
    // The series' session if one was made.
    SegmentationSession* find(const Volume& volume) const;
    std::vector<SegmentationSession*> sessions() const;

signals:
    // A series' session was made: the place to start saving it (SEG autosave).
    void sessionOpened(lucent::SegmentationSession* session);

private:
    std::string keyOf(const Volume& volume) const;

    std::map<std::string, SegmentationSession*> sessions_; // children
};

} // namespace lucent
