#include "ui/study/SeriesDrag.h"

#include <QJsonDocument>
#include <QJsonObject>
#include <QMimeData>

namespace lucent {

std::unique_ptr<QMimeData> seriesMimeData(const DraggedSeries& series) {
    auto data = std::make_unique<QMimeData>();
    const QJsonObject json{{QStringLiteral("path"), series.path},
                           {QStringLiteral("series"), series.series}};
    data->setData(QString::fromLatin1(kSeriesMimeType),
                  QJsonDocument(json).toJson(QJsonDocument::Compact));
    data->setText(series.series.isEmpty() ? series.path : series.series);
    return data;
}

std::optional<DraggedSeries> draggedSeries(const QMimeData& data) {
    const QString type = QString::fromLatin1(kSeriesMimeType);
    if (!data.hasFormat(type)) {
        return std::nullopt;
    }
    const QJsonObject json = QJsonDocument::fromJson(data.data(type)).object();
    DraggedSeries series{json.value(QStringLiteral("path")).toString(),
                         json.value(QStringLiteral("series")).toString()};
    if (series.path.isEmpty()) {
        return std::nullopt;
    }
    return series;
}

} // namespace lucent
