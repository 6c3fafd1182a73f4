#pragma once
// The study browser: patients -> studies -> series, each series with a
// thumbnail (its middle image), from the local study store and from the
// folders opened in this session. A click on a series asks to open it.

#include <QImage>
#include <QString>
#include <QWidget>

#include <optional>

#include "core/io/SeriesEntry.h"
#include "core/volume/Volume.h"

class QLabel;
class QTreeWidget;
class QTreeWidgetItem;

namespace lucent {

class SeriesThumbnailer;

class StudyBrowser : public QWidget {
    Q_OBJECT

public:
    static constexpr int kThumbnailSize = 96;
    static constexpr int kPathRole = Qt::UserRole;
    static constexpr int kSeriesRole = Qt::UserRole + 1;
    static constexpr int kSourceRole = Qt::UserRole + 2; // "folder" or "store"
    // True for a series that opens as a 2D image stack (colour, cine, localizer, lone
    // image), not as a volume.
    static constexpr int kStackRole = Qt::UserRole + 3;

    explicit StudyBrowser(QWidget* parent = nullptr);
    ~StudyBrowser() override;

    // The series loaded from path, marked as opened (bold, selected), with the
    // thumbnail of the loaded volume; the rest of path's series follow from a
    // scan in the background.
    void addSeries(const QString& path, const Volume& volume);
    // Scans path in the background and lists every series it holds.
    void addFolder(const QString& path);
    // The local study store to list; refreshStore() reads its index again.
    void setStoreFolder(const QString& folder);
    void refreshStore();

    // Series rows (of every patient and study).
    int count() const;
    QTreeWidget* tree() const { return tree_; }
    QTreeWidgetItem* findSeries(const QString& path, const QString& seriesUid) const;
    // Whether a listed series opens as a 2D image stack (kStackRole).
    bool opensAsStack(const QString& path, const QString& seriesUid) const;
    // Folder scans and thumbnails still on their way.
    int pending() const;

    // The acquisition plane (i right, j down) through the volume's centre, size x
    // size pixels, grey, in the volume's default window.
    static QImage thumbnail(const Volume& volume, int size = kThumbnailSize);

signals:
    // series: the series UID (empty: the path's default series).
    void openRequested(const QString& path, const QString& series);

private:
    QTreeWidgetItem* seriesItem(const SeriesInfo& info, const QString& path, const QString& source);
    void addEntry(const QString& path, const SeriesEntry& entry);
    void scanned(const QString& path, const std::vector<SeriesEntry>& entries,
                 const QString& error);
    void setThumbnail(const QString& path, const QString& seriesUid, const QImage& image);
    void updateStatus();

    QTreeWidget* tree_;
    QLabel* status_;
    SeriesThumbnailer* thumbnails_; // child
    QString storeFolder_;
    QStringList scannedFolders_;
    int scansRunning_ = 0;
    QString lastError_;
};

} // namespace lucent
