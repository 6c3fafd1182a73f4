#pragma once

#include <memory>
#include <optional>
#include <utility>

#include <QString>

class QMimeData;

namespace lucent {

// A series dragged from the study browser onto a viewport: where it is (a folder,
// file or store folder) and its id or UID there.
struct DraggedSeries {
    QString path;
    QString series;
};

inline constexpr const char* kSeriesMimeType = "application/x-lucent-series";

std::unique_ptr<QMimeData> seriesMimeData(const DraggedSeries& series);
// Nothing when the data holds no series of this format.
std::optional<DraggedSeries> draggedSeries(const QMimeData& data);

} // namespace lucent
