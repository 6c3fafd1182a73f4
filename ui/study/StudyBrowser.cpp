#include "ui/study/StudyBrowser.h"

#include <QMimeData>

#include "ui/study/SeriesDrag.h"

#include <filesystem>
#include <thread>

#include <QCoreApplication>
#include <QDate>
#include <QFileInfo>
#include <QHeaderView>
#include <QIcon>
#include <QLabel>
#include <QPixmap>
#include <QPointer>
#include <QTreeWidget>
#include <QVBoxLayout>

#include "core/io/Catalog.h"
#include "core/mpr/PlaneSampler.h"
#include "core/store/StudyStore.h"
#include "ui/study/SeriesThumbnailer.h"

namespace lucent {

namespace {

constexpr int kKeyRole = Qt::UserRole + 10; // patient and study rows: their grouping key

QString text(const std::string& s) {
    return QString::fromStdString(s);
}

QString patientLabel(const SeriesInfo& info) {
    const QString name = text(info.patientName).replace(QLatin1Char('^'), QLatin1Char(' '));
    const QString id = text(info.patientId);
    if (name.trimmed().isEmpty() && id.isEmpty()) {
        return QObject::tr("Unknown patient");
    }
    return id.isEmpty() ? name : QStringLiteral("%1 (%2)").arg(name.trimmed(), id);
}

QString studyLabel(const SeriesInfo& info, const std::string& studyDescription) {
    const QDate date = QDate::fromString(text(info.studyDate), QStringLiteral("yyyyMMdd"));
    QStringList parts;
    if (date.isValid()) {
        parts << date.toString(Qt::ISODate);
    }
    if (!studyDescription.empty()) {
        parts << text(studyDescription);
    }
    return parts.isEmpty() ? QObject::tr("Study %1").arg(text(info.studyUid)) : parts.join(" ");
}

QString dimsLabel(glm::ivec3 d) {
    return QStringLiteral("%1 x %2 x %3").arg(d.x).arg(d.y).arg(d.z);
}

QTreeWidgetItem* child(QTreeWidgetItem* parent, const QString& key, const QString& label) {
    for (int n = 0; n < parent->childCount(); ++n) {
        if (parent->child(n)->data(0, kKeyRole).toString() == key) {
            return parent->child(n);
        }
    }
    auto* item = new QTreeWidgetItem(parent, {label});
    item->setData(0, kKeyRole, key);
    item->setExpanded(true);
    return item;
}

} // namespace

namespace {

// The series rows drag as DraggedSeries, onto a viewport of the grid.
class SeriesTree : public QTreeWidget {
public:
    using QTreeWidget::QTreeWidget;

protected:
    QStringList mimeTypes() const override { return {QString::fromLatin1(kSeriesMimeType)}; }
    QMimeData* mimeData(const QList<QTreeWidgetItem*>& items) const override {
        for (const QTreeWidgetItem* item : items) {
            const QString path = item->data(0, StudyBrowser::kPathRole).toString();
            if (!path.isEmpty()) {
                return seriesMimeData({path, item->data(0, StudyBrowser::kSeriesRole).toString()})
                    .release(); // the drag owns it
            }
        }
        return nullptr;
    }
};

} // namespace

StudyBrowser::StudyBrowser(QWidget* parent)
    : QWidget(parent), tree_(new SeriesTree(this)), status_(new QLabel(this)),
      thumbnails_(new SeriesThumbnailer(kThumbnailSize, this)) {
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(tree_, 1);
    layout->addWidget(status_);
    tree_->setHeaderHidden(true);
    tree_->setIconSize(QSize(kThumbnailSize, kThumbnailSize));
    tree_->setWordWrap(true);
    tree_->setIndentation(12);
    tree_->setDragEnabled(true);
    tree_->setDragDropMode(QAbstractItemView::DragOnly);
    status_->setWordWrap(true);
    connect(tree_, &QTreeWidget::itemClicked, this, [this](QTreeWidgetItem* item) {
        const QString path = item->data(0, kPathRole).toString();
        if (!path.isEmpty()) {
            emit openRequested(path, item->data(0, kSeriesRole).toString());
        }
    });
    connect(thumbnails_, &SeriesThumbnailer::thumbnailReady, this, &StudyBrowser::setThumbnail);
    connect(thumbnails_, &SeriesThumbnailer::thumbnailFailed, this,
            [this](const QString& path, const QString& series, const QString& error) {
                if (QTreeWidgetItem* item = findSeries(path, series)) {
                    item->setToolTip(0, item->toolTip(0) + "\n" + error);
                }
                updateStatus();
            });
    updateStatus();
}

StudyBrowser::~StudyBrowser() = default;

bool StudyBrowser::opensAsStack(const QString& path, const QString& seriesUid) const {
    const QTreeWidgetItem* item = findSeries(path, seriesUid);
    return item != nullptr && item->data(0, kStackRole).toBool();
}

QTreeWidgetItem* StudyBrowser::seriesItem(const SeriesInfo& info, const QString& path,
                                          const QString& source) {
    const QString uid = text(info.seriesUid);
    if (QTreeWidgetItem* existing = findSeries(path, uid)) {
        return existing;
    }
    const QString patientKey = text(info.patientId + "|" + info.patientName);
    QTreeWidgetItem* patient = nullptr;
    for (int n = 0; n < tree_->topLevelItemCount() && patient == nullptr; ++n) {
        if (tree_->topLevelItem(n)->data(0, kKeyRole).toString() == patientKey) {
            patient = tree_->topLevelItem(n);
        }
    }
    if (patient == nullptr) {
        patient = new QTreeWidgetItem(tree_, {patientLabel(info)});
        patient->setData(0, kKeyRole, patientKey);
        patient->setExpanded(true);
    }
    // Non-DICOM files have no study: each is its own.
    const QString studyKey = info.studyUid.empty() ? path : text(info.studyUid);
    QTreeWidgetItem* study = child(patient, studyKey, studyLabel(info, {}));
    auto* item = new QTreeWidgetItem(study);
    item->setData(0, kPathRole, path);
    item->setData(0, kSeriesRole, uid);
    item->setData(0, kSourceRole, source);
    item->setToolTip(0, path);
    return item;
}

QTreeWidgetItem* StudyBrowser::findSeries(const QString& path, const QString& seriesUid) const {
    for (QTreeWidgetItemIterator it(tree_); *it != nullptr; ++it) {
        if ((*it)->data(0, kPathRole).toString() == path &&
            (*it)->data(0, kSeriesRole).toString() == seriesUid) {
            return *it;
        }
    }
    return nullptr;
}

int StudyBrowser::count() const {
    int n = 0;
    for (QTreeWidgetItemIterator it(tree_); *it != nullptr; ++it) {
        n += (*it)->data(0, kPathRole).toString().isEmpty() ? 0 : 1;
    }
    return n;
}

int StudyBrowser::pending() const {
    return scansRunning_ + thumbnails_->pending();
}

void StudyBrowser::addSeries(const QString& path, const Volume& volume) {
    QTreeWidgetItem* item = seriesItem(volume, path, QStringLiteral("folder"));
    const QString series = text(volume.seriesUid);
    item->setText(
        0, QStringLiteral("%1 %2\n%3")
               .arg(text(volume.modality), text(volume.description), dimsLabel(volume.dims()))
               .trimmed());
    QFont bold = item->font(0);
    bold.setBold(true);
    item->setFont(0, bold);
    const QImage image = thumbnail(volume);
    thumbnails_->remember(path, series, image);
    setThumbnail(path, series, image);
    tree_->setCurrentItem(item);
    addFolder(path);
}

void StudyBrowser::addEntry(const QString& path, const SeriesEntry& entry) {
    QTreeWidgetItem* item = seriesItem(entry, path, QStringLiteral("folder"));
    item->setData(0, kStackRole, entry.kind != SeriesKind::Volume);
    if (item->text(0).isEmpty()) {
        QString label =
            QStringLiteral("%1 %2").arg(text(entry.modality), text(entry.description)).trimmed();
        if (entry.kind == SeriesKind::Localizer) {
            label += tr(" (localizer)");
        } else if (entry.kind == SeriesKind::Stack || entry.kind == SeriesKind::Image) {
            label += tr(" (images)");
        }
        item->setText(0, label.trimmed() + "\n" + dimsLabel(entry.geometry.dims));
    }
    thumbnails_->request(path, text(entry.seriesUid), entry);
}

void StudyBrowser::addFolder(const QString& path) {
    if (scannedFolders_.contains(path)) {
        return;
    }
    scannedFolders_ << path;
    ++scansRunning_;
    updateStatus();
    const QPointer<StudyBrowser> self(this);
    std::thread([self, path] {
        std::vector<SeriesEntry> entries;
        QString error;
        try {
            LoadControl control;
            control.threads = 1;
            entries = scanPath(path.toStdString(), control).series;
        } catch (const std::exception& e) {
            error = QString::fromStdString(e.what());
        }
        QMetaObject::invokeMethod(
            qApp,
            [self, path, entries = std::move(entries), error] {
                if (self) {
                    self->scanned(path, entries, error);
                }
            },
            Qt::QueuedConnection);
    }).detach();
}

void StudyBrowser::scanned(const QString& path, const std::vector<SeriesEntry>& entries,
                           const QString& error) {
    --scansRunning_;
    if (!error.isEmpty()) {
        lastError_ = error;
    }
    for (const SeriesEntry& entry : entries) {
        addEntry(path, entry);
    }
    updateStatus();
}

void StudyBrowser::setStoreFolder(const QString& folder) {
    storeFolder_ = folder;
    refreshStore();
}

void StudyBrowser::refreshStore() {
    if (storeFolder_.isEmpty() || !std::filesystem::exists(storeFolder_.toStdString())) {
        updateStatus();
        return;
    }
    std::vector<StoredSeries> all;
    try {
        all = StudyStore(storeFolder_.toStdString()).listSeries();
    } catch (const StoreError& e) {
        lastError_ = text(e.what());
        updateStatus();
        return;
    }
    for (const StoredSeries& s : all) {
        const QString folder = QString::fromStdString(s.folder.string());
        QTreeWidgetItem* item = seriesItem(s.info, folder, QStringLiteral("store"));
        // The store knows the study's description, which a series' own facts lack.
        item->parent()->setText(0, studyLabel(s.info, s.studyDescription));
        const QString state = s.complete ? tr("in store")
                              : s.expected > 0
                                  ? tr("in store, %1 of %2 images").arg(s.stored).arg(s.expected)
                                  : tr("in store, %1 images").arg(s.stored);
        item->setText(0, QStringLiteral("%1 %2\n%3")
                             .arg(text(s.info.modality), text(s.info.description), state)
                             .trimmed());
        if (s.stored > 0) {
            thumbnails_->request(folder, text(s.info.seriesUid));
        }
    }
    updateStatus();
}

void StudyBrowser::setThumbnail(const QString& path, const QString& seriesUid,
                                const QImage& image) {
    if (QTreeWidgetItem* item = findSeries(path, seriesUid)) {
        item->setIcon(0, QIcon(QPixmap::fromImage(image)));
    }
    updateStatus();
}

void StudyBrowser::updateStatus() {
    QString line = tr("%n series", nullptr, count());
    if (pending() > 0) {
        line += tr(", reading...");
    }
    if (!lastError_.isEmpty()) {
        line += "\n" + lastError_;
    }
    status_->setText(line);
}

QImage StudyBrowser::thumbnail(const Volume& volume, int size) {
    QImage image(size, size, QImage::Format_Grayscale8);
    image.fill(0);
    if (volume.empty()) {
        return image;
    }
    // The plane the images were acquired in (rows along i, columns along j),
    // through the middle: what the series looks like on the scanner.
    const VolumeGeometry& geometry = volume.geometry();
    SlicePlane plane;
    plane.u = glm::normalize(geometry.direction[0]);
    plane.v = glm::normalize(geometry.direction[1]);
    plane.centre = volumeCentre(geometry);
    plane.width = plane.height = size;
    plane.pixelSize = fitPixelSize(geometry, plane.u, plane.v, size, size);
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

} // namespace lucent
