#pragma once
// The local study store as a patient -> study -> series tree, read from its
// SQLite index, with each series' completeness. Double-click opens a series.

#include <QWidget>

class QLabel;
class QTreeWidget;

namespace lucent {

class StoreBrowser : public QWidget {
    Q_OBJECT

public:
    static constexpr int kFolderRole = Qt::UserRole;
    static constexpr int kSeriesUidRole = Qt::UserRole + 1;

    explicit StoreBrowser(QWidget* parent = nullptr);

    void setStoreFolder(const QString& folder);
    // Reads the index again.
    void refresh();
    QTreeWidget* tree() const { return tree_; }

signals:
    void openSeries(const QString& folder, const QString& seriesUid);

private:
    QString folder_;
    QTreeWidget* tree_;
    QLabel* status_;
};

} // namespace lucent
