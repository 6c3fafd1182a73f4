#pragma once

#include <cstddef>
#include <list>
#include <memory>
#include <set>
#include <thread>
#include <vector>

#include <QObject>
#include <QString>

#include "core/stack/ImageStack.h"
#include "core/volume/Volume.h"

namespace lucent {

class SeriesSession;

// The series loaded for the viewport grid (volumes, and 2D image stacks for what is
// no volume: colour, cine, localizers, lone images), one SeriesSession each, found by where
// they came from (path and series id/UID) or by series UID. Loads run in the
// background, one worker each, and end in ready() or failed(). Sessions that no
// viewport shows are dropped by trim() once all sessions together hold more than a
// budget, oldest first; asking for one again loads it again.
class SeriesLibrary : public QObject {
    Q_OBJECT

public:
    explicit SeriesLibrary(QObject* parent = nullptr);
    ~SeriesLibrary() override;

    // The loaded session of path's series (empty: its default series), or nullptr.
    SeriesSession* find(const QString& path, const QString& series) const;
    SeriesSession* findUid(const std::string& seriesUid) const;
    // Loads unless loaded or loading; ready() comes at once (queued) when loaded.
    void request(const QString& path, const QString& series);
    // A volume loaded elsewhere (the main loader) becomes a session here.
    SeriesSession* adopt(std::shared_ptr<const Volume> volume, const QString& path,
                         const QString& series);
    // Another session of the same loaded volume, with a crosshair and window of its
    // own: two viewports of one series in different windows (lung and soft tissue).
    SeriesSession* sibling(SeriesSession* session);
    bool loading() const { return !pending_.empty(); }
    // Bytes of voxels held by every session (a volume shared by siblings once).
    std::size_t bytes() const;
    int count() const { return static_cast<int>(sessions_.size()); }
    // Every loaded session, oldest first.
    std::vector<SeriesSession*> sessions() const { return {sessions_.begin(), sessions_.end()}; }
    // Drops sessions not in `shown`, least recently loaded first, while all hold
    // more than budgetBytes. Returns how many were dropped.
    int trim(const std::set<const SeriesSession*>& shown, std::size_t budgetBytes);

signals:
    void ready(const QString& path, const QString& series, lucent::SeriesSession* session);
    void failed(const QString& path, const QString& series, const QString& error);
    // Once per load, what the reader should know about the values shown: a PET series that
    // could not be shown in SUVbw, and why (petDisplayNotice).
    void notice(const QString& text);

private:
    struct Pending {
        QString path;
        QString series;
        std::jthread worker;
    };
    void finish(const QString& path, const QString& series, std::shared_ptr<Volume> volume,
                std::shared_ptr<ImageStack> stack, const QString& error);

    std::list<SeriesSession*> sessions_; // children, oldest first
    std::list<Pending> pending_;         // last: joined before the rest goes
};

} // namespace lucent
