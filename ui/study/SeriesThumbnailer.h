#pragma once
// Thumbnails of series made off the GUI thread: the middle image of a series,
// decoded on one worker thread (a browser full of series must not take the
// cores the views need), delivered by a signal, kept while the object lives.

#include <QHash>
#include <QImage>
#include <QObject>
#include <QString>
#include <QThreadPool>

#include <memory>
#include <optional>
#include <stop_token>

#include "core/io/SeriesEntry.h"

namespace lucent {

class SeriesThumbnailer : public QObject {
    Q_OBJECT

public:
    explicit SeriesThumbnailer(int size, QObject* parent = nullptr);
    ~SeriesThumbnailer() override;

    // Asks for the thumbnail of the series `seriesUid` under `path` (empty UID:
    // the path's default series); `entry`, when given, saves scanning the path.
    // Answered at once from the cache, or later by thumbnailReady/thumbnailFailed.
    void request(const QString& path, const QString& seriesUid,
                 std::optional<SeriesEntry> entry = std::nullopt);
    // Keeps a thumbnail made elsewhere (e.g. of a series already loaded).
    void remember(const QString& path, const QString& seriesUid, const QImage& image);
    // Jobs queued or running.
    int pending() const { return pending_; }

    static QString key(const QString& path, const QString& seriesUid) {
        return path + QLatin1Char('|') + seriesUid;
    }

signals:
    void thumbnailReady(const QString& path, const QString& seriesUid, const QImage& image);
    void thumbnailFailed(const QString& path, const QString& seriesUid, const QString& error);

private:
    void finish(const QString& path, const QString& seriesUid, const QImage& image,
                const QString& error);

    int size_;
    QHash<QString, QImage> cache_;
    QHash<QString, bool> asked_;
    int pending_ = 0;
    std::stop_source stop_;
    QThreadPool pool_; // last: its jobs are waited for before the rest goes
};

} // namespace lucent
