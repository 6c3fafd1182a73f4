#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <QObject>
#include <QString>
#include <QTimer>

#include "core/segdicom/SegmentationArchive.h"

namespace lucent {

class Segmentation;
class StudyStore;

// Keeps each segmented series' segments in the local study store as Lucent's DICOM SEG
// (core/segdicom/SegmentationArchive), as the reader works: every change of a tracked
// Segmentation (its revision()) is saved kDelayMs after the last edit, and at once on
// flush(), detach() and when this object goes (the window closes). The session may call
// changed() after an edit; a cheap poll of revision() every kPollMs catches the rest, since
// Segmentation is plain C++ with no signal. load() gives what the store holds for a series
// (Lucent's SEG and the SEGs of other programs) for the session to add. A series that is not
// in the store keeps its segments for the session only, and message() says so.
class SegmentationAutosave : public QObject {
    Q_OBJECT

public:
    static constexpr int kDelayMs = 600;
    static constexpr int kPollMs = 250;

    explicit SegmentationAutosave(QString storeFolder, QObject* parent = nullptr);
    ~SegmentationAutosave() override;

    void setStoreFolder(const QString& folder);

    // The SEGs the store holds for the series, read onto `grid`; errors come as message().
    SegmentationArchive::LoadResult load(const QString& seriesUid, const VolumeGeometry& grid);

    // Tracks `segmentation` (not owned: detach() before it goes), of the stored series
    // `seriesUid`, from its present revision on (what load() gave is not saved again). False,
    // with a message, when the series is not in the store.
    bool attach(Segmentation* segmentation, const QString& seriesUid);
    // Saves what is pending and stops tracking.
    void detach(const Segmentation* segmentation);
    // Saves every tracked segmentation changed since its last save now.
    void flush();

public slots:
    // An edit was made: the save waits kDelayMs for the next one.
    void changed();

signals:
    void message(const QString& text, int timeoutMs);
    // A series' SEG was written ("" when its last segment went and the SEG with it).
    void saved(const QString& seriesUid, const QString& segInstanceUid);

private:
    struct Tracked {
        Segmentation* segmentation = nullptr;
        QString seriesUid;
        std::uint64_t savedRevision = 0;
        std::uint64_t seenRevision = 0;
    };
    void save(Tracked& tracked);
    void poll();
    bool storeExists() const;
    // The store and its archive, opened once: opening a store tidies its tmp/ folder, and the
    // archive reads each series' image headers once.
    SegmentationArchive& archive();

    QString folder_;
    std::unique_ptr<StudyStore> store_;
    std::unique_ptr<SegmentationArchive> archive_;
    std::vector<Tracked> tracked_;
    QTimer timer_;
    QTimer poll_;
};

} // namespace lucent
