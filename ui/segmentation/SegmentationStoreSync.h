#pragma once
// The Segment Editor's sessions kept in the study store: when a series' session opens, the
// SEGs the store holds for it (Lucent's, then other programs') are read onto it, with undo
// starting after them, and from then on every edit is saved as Lucent's SEG by the autosave.

#include <QObject>
#include <QSet>

namespace lucent {

class SegmentationAutosave;
class SegmentationSession;
class SegmentationSessions;

class SegmentationStoreSync : public QObject {
    Q_OBJECT

public:
    // Neither is owned; the autosave must outlive the sessions' segmentations or be flushed
    // and detached first (detachAll()).
    SegmentationStoreSync(SegmentationSessions* sessions, SegmentationAutosave* autosave,
                          QObject* parent = nullptr);

    // Reads the stored SEGs onto the session and starts saving it. Done by itself for every
    // session opened after construction.
    void track(SegmentationSession* session);
    // Saves what is pending and stops saving every session (before they go).
    void detachAll();

signals:
    void message(const QString& text, int timeoutMs);

private:
    SegmentationSessions* sessions_;
    SegmentationAutosave* autosave_;
    QSet<const SegmentationSession*> told_; // that its segments are not stored
};

} // namespace lucent
