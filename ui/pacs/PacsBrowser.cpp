#include "ui/pacs/PacsBrowser.h"

#include <QAction>
#include <QDirIterator>
#include <QDockWidget>
#include <QMainWindow>
#include <QMenu>
#include <QPushButton>
#include <QSettings>
#include <QSplitter>
#include <QTabWidget>
#include <QVBoxLayout>

#include "core/pacs/PacsService.h"
#include "ui/pacs/ExportDialog.h"
#include "ui/pacs/PacsNodeSettings.h"
#include "ui/pacs/PacsQueryPanel.h"
#include "ui/pacs/RetrievalProgress.h"
#include "ui/pacs/StoreBrowser.h"

namespace lucent {

PacsBrowser::PacsBrowser(const QString& settingsFile, QWidget* parent)
    : QWidget(parent),
      settings_(
          settingsFile.isEmpty()
              ? std::make_unique<QSettings>(QStringLiteral("lucent"), QStringLiteral("lucent"))
              : std::make_unique<QSettings>(settingsFile, QSettings::IniFormat)),
      service_(new PacsService(this)), tabs_(new QTabWidget(this)),
      query_(new PacsQueryPanel(service_, this)), progress_(new RetrievalProgress(service_, this)),
      store_(new StoreBrowser(this)) {
    auto* nodes = new QPushButton(tr("PACS &nodes..."), this);
    nodes->setObjectName(QStringLiteral("editNodes"));
    auto* pacsPage = new QSplitter(Qt::Vertical, this);
    pacsPage->addWidget(query_);
    pacsPage->addWidget(progress_);
    pacsPage->setStretchFactor(0, 3);
    pacsPage->setStretchFactor(1, 1);
    tabs_->addTab(pacsPage, tr("PACS"));
    tabs_->addTab(store_, tr("Local store"));
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(nodes, 0, Qt::AlignRight);
    layout->addWidget(tabs_, 1);
    connect(nodes, &QPushButton::clicked, this, &PacsBrowser::showNodeSettings);
    connect(service_, &PacsService::seriesArrived, this, &PacsBrowser::openSeries);
    connect(service_, &PacsService::retrievalFinished, store_, &StoreBrowser::refresh);
    connect(store_, &StoreBrowser::openSeries, this, &PacsBrowser::openSeries);
    connect(store_, &StoreBrowser::sendRequested, this, &PacsBrowser::sendSeries);
    connect(store_, &StoreBrowser::exportRequested, this, &PacsBrowser::exportSeries);
    setConfig(PacsConfig::load(*settings_));
}

PacsBrowser::~PacsBrowser() = default;

void PacsBrowser::setConfig(const PacsConfig& config) {
    config_ = config;
    service_->setConfig(config_);
    query_->setNodes(config_.nodes);
    store_->setStoreFolder(config_.storeFolder);
    QStringList names;
    for (const PacsNodeConfig& n : config_.nodes) {
        names << n.name;
    }
    store_->setNodeNames(names);
}

QString PacsBrowser::sendSeries(int node, const QStringList& folders, const QString& label) {
    if (node < 0 || node >= config_.nodes.size()) {
        return {};
    }
    QStringList files;
    for (const QString& folder : folders) {
        QDirIterator it(folder, QDir::Files, QDirIterator::Subdirectories);
        while (it.hasNext()) {
            files << it.next();
        }
    }
    files.sort();
    const PacsNodeConfig& target = config_.nodes[node];
    const QString key = QStringLiteral("send-%1").arg(++sends_);
    tabs_->setCurrentIndex(0); // the transfers list is on the PACS page
    service_->send(target, key, tr("%1 to %2").arg(label, target.name), files);
    return key;
}

ExportDialog* PacsBrowser::exportSeries(const QStringList& folders, const QString& label) {
    auto* dialog = new ExportDialog(folders, label, this);
    dialog->setWindowFlag(Qt::Dialog);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    dialog->show();
    return dialog;
}

PacsNodeSettings* PacsBrowser::showNodeSettings() {
    if (nodeSettings_ == nullptr) {
        nodeSettings_ = new PacsNodeSettings(service_, settings_.get(), this);
        nodeSettings_->setWindowFlag(Qt::Dialog);
        connect(nodeSettings_, &PacsNodeSettings::saved, this, &PacsBrowser::setConfig);
    }
    nodeSettings_->show();
    nodeSettings_->raise();
    return nodeSettings_;
}

PacsBrowser* PacsBrowser::addDock(QMainWindow* window, QMenu* menu) {
    auto* dock = new QDockWidget(tr("PACS and local store"), window);
    dock->setObjectName(QStringLiteral("pacsDock"));
    auto* browser = new PacsBrowser({}, dock);
    dock->setWidget(browser);
    window->addDockWidget(Qt::LeftDockWidgetArea, dock);
    dock->hide();
    QAction* toggle = dock->toggleViewAction();
    toggle->setText(tr("&Query / Retrieve..."));
    toggle->setShortcut(QKeySequence(tr("Ctrl+Shift+P")));
    menu->addAction(toggle);
    menu->addAction(tr("PACS &nodes..."), browser, [browser] { browser->showNodeSettings(); });
    return browser;
}

} // namespace lucent
