#pragma once

#include <QImage>
#include <QString>
#include <QWidget>

#include "core/volume/Volume.h"

class QListWidget;
class QListWidgetItem;

namespace lucent {

// The series opened in this session, newest first: a thumbnail (the middle axial
// slice, small, in the volume's default window), the description and the
// dimensions. A click on one asks to open it again.
class StudyBrowser : public QWidget {
    Q_OBJECT

public:
    static constexpr int kThumbnailSize = 96;

    explicit StudyBrowser(QWidget* parent = nullptr);

    // Adds the series loaded from path (or moves it to the top when it is there).
    void addSeries(const QString& path, const Volume& volume);
    int count() const;
    QListWidget* list() const { return list_; }

    // The axial plane through the volume's centre, size x size pixels, grey.
    static QImage thumbnail(const Volume& volume, int size = kThumbnailSize);

signals:
    // series: the series UID (empty: the path's default series).
    void openRequested(const QString& path, const QString& series);

private:
    void open(const QListWidgetItem* item);

    QListWidget* list_;
};

} // namespace lucent
