#include "ui/viewports/SeriesSession.h"

#include "ui/mpr/MprCursor.h"

namespace lucent {

SeriesSession::SeriesSession(std::shared_ptr<const Volume> volume, QString path, QString series,
                             QObject* parent)
    : QObject(parent), volume_(std::move(volume)), path_(std::move(path)),
      series_(std::move(series)), cursor_(new MprCursor(this)) {
    centreOn(*cursor_, *volume_);
}

SeriesSession::SeriesSession(std::shared_ptr<const ImageStack> stack, QString path, QString series,
                             QObject* parent)
    : QObject(parent), stack_(std::move(stack)), path_(std::move(path)), series_(std::move(series)),
      cursor_(new MprCursor(this)) {}

const SeriesInfo& SeriesSession::info() const {
    return volume_ ? static_cast<const SeriesInfo&>(*volume_)
                   : static_cast<const SeriesInfo&>(*stack_);
}

std::size_t SeriesSession::bytes() const {
    return volume_ ? volume_->byteCount()
                   : stack_->grey.size() * sizeof(float) + stack_->rgb.size();
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
    if (!info().studyDate.empty()) {
        parts << QString::fromStdString(formatStudyDate(info().studyDate));
    }
    return parts.join(QStringLiteral(" | "));
}

} // namespace lucent
