#pragma once

#include <cstddef>
#include <memory>

#include <QObject>
#include <QString>

#include "core/volume/Volume.h"

namespace lucent {

class MprCursor;

// One series loaded for the viewport grid: its volume and its own crosshair, window
// and plane rotations (MprCursor), shared by every viewport that shows it. Viewports
// of other series follow it only through the links of ViewportLinks.
class SeriesSession : public QObject {
    Q_OBJECT

public:
    // path and series: where it was loaded from (series: an id or UID of that path).
    SeriesSession(std::shared_ptr<const Volume> volume, QString path, QString series,
                  QObject* parent = nullptr);

    const std::shared_ptr<const Volume>& volume() const { return volume_; }
    MprCursor* cursor() const { return cursor_; }
    const QString& path() const { return path_; }
    const QString& series() const { return series_; }
    QString seriesUid() const { return QString::fromStdString(volume_->seriesUid); }
    // What its voxels cost in memory.
    std::size_t bytes() const { return volume_->byteCount(); }
    // "CT Thorax 1.0 | 2024-03-01": what a viewport's corner names.
    QString title() const;

private:
    std::shared_ptr<const Volume> volume_;
    QString path_;
    QString series_;
    MprCursor* cursor_;
};

} // namespace lucent
