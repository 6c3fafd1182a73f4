#include "ui/StudyBrowser.h"

#include <memory>

#include <QFileInfo>
#include <QIcon>
#include <QListWidget>
#include <QPixmap>
#include <QVBoxLayout>

#include "core/mpr/PlaneSampler.h"

namespace lucent {

namespace {

constexpr int kPathRole = Qt::UserRole;
constexpr int kSeriesRole = Qt::UserRole + 1;

QString label(const QString& path, const Volume& volume) {
    const glm::ivec3 d = volume.dims();
    const QString series = QStringLiteral("%1 %2")
                               .arg(QString::fromStdString(volume.modality),
                                    QString::fromStdString(volume.description))
                               .trimmed();
    QStringList lines;
    if (!volume.patientName.empty()) {
        lines << QString::fromStdString(volume.patientName);
    }
    lines << (series.isEmpty() ? QFileInfo(path).fileName() : series);
    lines << QStringLiteral("%1 x %2 x %3").arg(d.x).arg(d.y).arg(d.z);
    return lines.join(QLatin1Char('\n'));
}

} // namespace

StudyBrowser::StudyBrowser(QWidget* parent) : QWidget(parent), list_(new QListWidget(this)) {
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(list_);
    list_->setIconSize(QSize(kThumbnailSize, kThumbnailSize));
    list_->setSpacing(2);
    list_->setWordWrap(true);
    connect(list_, &QListWidget::itemClicked, this, &StudyBrowser::open);
}

void StudyBrowser::addSeries(const QString& path, const Volume& volume) {
    const QString series = QString::fromStdString(volume.seriesUid);
    for (int n = 0; n < list_->count(); ++n) {
        const QListWidgetItem* item = list_->item(n);
        if (item->data(kPathRole).toString() == path &&
            item->data(kSeriesRole).toString() == series) {
            const std::unique_ptr<QListWidgetItem> old(list_->takeItem(n));
            break;
        }
    }
    auto item = std::make_unique<QListWidgetItem>(QIcon(QPixmap::fromImage(thumbnail(volume))),
                                                  label(path, volume));
    item->setData(kPathRole, path);
    item->setData(kSeriesRole, series);
    item->setToolTip(path);
    list_->insertItem(0, item.get());
    list_->setCurrentItem(item.release()); // the list owns it now
}

int StudyBrowser::count() const {
    return list_->count();
}

QImage StudyBrowser::thumbnail(const Volume& volume, int size) {
    QImage image(size, size, QImage::Format_Grayscale8);
    image.fill(0);
    if (volume.empty()) {
        return image;
    }
    const VolumeGeometry& geometry = volume.geometry();
    const SlicePlane plane =
        standardPlane(geometry, Orientation::Axial, volumeCentre(geometry), size, size);
    const std::vector<float> samples = sampleImage(volume, plane);
    const WindowLevel window = defaultWindow(volume);
    for (int y = 0; y < size; ++y) {
        uchar* row = image.scanLine(y);
        for (int x = 0; x < size; ++x) {
            row[x] = windowToGrey(samples[static_cast<std::size_t>(y * size + x)], window.center,
                                  window.width);
        }
    }
    return image;
}

void StudyBrowser::open(const QListWidgetItem* item) {
    if (item != nullptr) {
        emit openRequested(item->data(kPathRole).toString(), item->data(kSeriesRole).toString());
    }
}

} // namespace lucent
