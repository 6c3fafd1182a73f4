#pragma once

#include <cstddef>
#include <memory>

#include <QObject>
#include <QString>

#include "core/stack/ImageStack.h"
#include "core/volume/Volume.h"

namespace lucent {

class MprCursor;

// One series loaded for the viewport grid: its volume and its own crosshair, window
// and plane rotations (MprCursor), shared by every viewport that shows it, or a 2D
// image stack (colour, cine, localizer, lone image) that a StackView shows. Viewports
// of other series follow it only through the links of ViewportLinks.
class SeriesSession : public QObject {
    Q_OBJECT

public:
    // path and series: where it was loaded from (series: an id or UID of that path).
    SeriesSession(std::shared_ptr<const Volume> volume, QString path, QString series,
                  QObject* parent = nullptr);
    SeriesSession(std::shared_ptr<const ImageStack> stack, QString path, QString series,
                  QObject* parent = nullptr);

    // Exactly one of the two is set.
    const std::shared_ptr<const Volume>& volume() const { return volume_; }
    const std::shared_ptr<const ImageStack>& stack() const { return stack_; }
    const SeriesInfo& info() const;
    MprCursor* cursor() const { return cursor_; }
    const QString& path() const { return path_; }
    const QString& series() const { return series_; }
    QString seriesUid() const { return QString::fromStdString(info().seriesUid); }
    // What its voxels or pixels cost in memory.
    std::size_t bytes() const;
    // "CT Thorax 1.0 | 2024-03-01": what a viewport's corner names.
    QString title() const;

private:
    std::shared_ptr<const Volume> volume_;
    std::shared_ptr<const ImageStack> stack_;
    QString path_;
    QString series_;
    MprCursor* cursor_;
};

} // namespace lucent
