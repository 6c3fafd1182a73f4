#include "ui/segmentation/SegmentationStoreSync.h"

#include <QSignalBlocker>

#include "core/segdicom/SegmentationDicom.h"
#include "ui/segmentation/SegmentationAutosave.h"
#include "ui/segmentation/SegmentationSession.h"

namespace lucent {

SegmentationStoreSync::SegmentationStoreSync(SegmentationSessions* sessions,
                                             SegmentationAutosave* autosave, QObject* parent)
    : QObject(parent), sessions_(sessions), autosave_(autosave) {
    connect(sessions_, &SegmentationSessions::sessionOpened, this, &SegmentationStoreSync::track);
    connect(autosave_, &SegmentationAutosave::message, this, &SegmentationStoreSync::message);
}

void SegmentationStoreSync::track(SegmentationSession* session) {
    if (session == nullptr || !session->volume()) {
        return;
    }
    const QString uid = QString::fromStdString(session->volume()->seriesUid);
    Segmentation& segmentation = session->segmentation();
    const SegmentationArchive::LoadResult held = autosave_->load(uid, segmentation.geometry());
    int segments = 0;
    int locked = 0;
    for (const SegmentationArchive::Loaded& seg : held.loaded) {
        const std::vector<std::uint32_t> ids = addSegments(segmentation, seg.segmentation.segments);
        segments += static_cast<int>(ids.size());
        // What Lucent would not write back as it was (FRACTIONAL) opens locked: effects
        // leave it alone until the reader unlocks it and makes it a binary segment.
        for (const std::uint32_t id :
             seg.segmentation.readOnly ? ids : std::vector<std::uint32_t>{}) {
            segmentation.setLocked(id, true);
            ++locked;
        }
    }
    if (segments > 0) {
        segmentation.clearHistory();
        session->notifyChanged();
        emit message(tr("%n stored segment(s) opened on the series", nullptr, segments) +
                         (locked > 0 ? tr(", %n locked (read-only in their SEG)", nullptr, locked)
                                     : QString()),
                     5000);
    }
    // Saved from now on (attach() starts after what was loaded). A series outside the store
    // keeps its segments for this session only: said at its first edit, not each time it is
    // shown (the autosave would say it now).
    bool stored = false;
    {
        const QSignalBlocker quiet(autosave_);
        stored = autosave_->attach(&segmentation, uid);
    }
    connect(session, &SegmentationSession::segmentsChanged, this, [this, session, stored] {
        if (!stored && !told_.contains(session)) {
            told_.insert(session);
            emit message(tr("Segments of this series are kept for this session only: it is not "
                            "in the study store"),
                         8000);
        }
        autosave_->changed();
    });
}

void SegmentationStoreSync::detachAll() {
    for (SegmentationSession* session : sessions_->sessions()) {
        autosave_->detach(&session->segmentation());
    }
}

} // namespace lucent
