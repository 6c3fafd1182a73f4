#pragma once
// The local study store as a patient -> study -> series tree, read from its
// SQLite index, with each series' completeness. Double-click opens a series;
// the context menu of a series, study or patient sends it to a PACS node or
// exports it.

#include <QStringList>
#include <QWidget>

class QLabel;
class QMenu;
class QTreeWidget;
class QTreeWidgetItem;

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
    // The PACS nodes offered by "Send to" (their names, in the order of the config).
    void setNodeNames(const QStringList& names) { nodeNames_ = names; }
    // The context menu of an item: "Send to NAME" per node (objectName
    // sendTo0, sendTo1, ...) and "Export..." (export).
    void fillContextMenu(QMenu& menu, QTreeWidgetItem* item);
    // The series folders of an item: its own, or those of the series below it.
    static QStringList seriesFolders(const QTreeWidgetItem* item);

signals:
    void openSeries(const QString& folder, const QString& seriesUid);
    void sendRequested(int node, const QStringList& folders, const QString& label);
    void exportRequested(const QStringList& folders, const QString& label);

private:
    QString folder_;
    QStringList nodeNames_;
    QTreeWidget* tree_;
    QLabel* status_;
};

} // namespace lucent
