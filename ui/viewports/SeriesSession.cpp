#include "ui/viewports/SeriesSession.h"

#include "ui/mpr/MprCursor.h"

namespace lucent {

SeriesSession::SeriesSession(std::shared_ptr<const Volume> volume, QString path, QString series,
                             QObject* parent)
    : QObject(parent), volume_(std::move(volume)), path_(std::move(path)),
      series_(std::move(series)), cursor_(new MprCursor(this)) {
    centreOn(*cursor_, *volume_);
}

QString SeriesSession::title() const {
    QStringList parts;
    const QString series = QStringLiteral("%1 %2")
                               .arg(QString::fromStdString(volume_->modality),
                                    QString::fromStdString(volume_->description))
                               .trimmed();
    if (!series.isEmpty()) {
        parts << series;
    }
    if (!volume_->studyDate.empty()) {
        parts << QString::fromStdString(formatStudyDate(volume_->studyDate));
    }
    return parts.join(QStringLiteral(" | "));
}

} // namespace lucent
