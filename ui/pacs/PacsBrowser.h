#pragma once
// The PACS browser of the workstation: query panel, retrieval progress and the
// local study store, over one PacsService. Series that arrive complete (and
// series double-clicked in the store) are offered to open through openSeries.

#include <memory>

#include <QWidget>

#include "core/pacs/PacsConfig.h"

class QMainWindow;
class QMenu;
class QSettings;
class QTabWidget;

namespace lucent {

class ExportDialog;
class PacsNodeSettings;
class PacsQueryPanel;
class PacsService;
class RetrievalProgress;
class StoreBrowser;

class PacsBrowser : public QWidget {
    Q_OBJECT

public:
    // settingsFile: an INI file for the PACS settings; empty: the user's QSettings.
    explicit PacsBrowser(const QString& settingsFile = {}, QWidget* parent = nullptr);
    ~PacsBrowser() override;

    // Adds the browser as a dock of window (hidden until asked for) and its
    // entries to menu. Returns the browser; its parent is the dock.
    static PacsBrowser* addDock(QMainWindow* window, QMenu* menu);

    void setConfig(const PacsConfig& config);
    const PacsConfig& config() const { return config_; }
    // The node settings dialog (non-modal, created on first use).
    PacsNodeSettings* showNodeSettings();

    PacsService* service() const { return service_; }
    PacsQueryPanel* queryPanel() const { return query_; }
    RetrievalProgress* progress() const { return progress_; }
    StoreBrowser* store() const { return store_; }
    // Sends the instances of stored series to the node at `node` in the config;
    // the transfer shows in the progress list. Returns its key there.
    QString sendSeries(int node, const QStringList& folders, const QString& label);
    // The export dialog for stored series (non-modal, deleted when closed).
    ExportDialog* exportSeries(const QStringList& folders, const QString& label);

signals:
    void openSeries(const QString& folder, const QString& seriesUid);

private:
    std::unique_ptr<QSettings> settings_;
    PacsConfig config_;
    PacsService* service_;
    QTabWidget* tabs_;
    PacsQueryPanel* query_;
    RetrievalProgress* progress_;
    StoreBrowser* store_;
    PacsNodeSettings* nodeSettings_ = nullptr;
    int sends_ = 0;
};

} // namespace lucent
