#include "ui/pacs/StoreBrowser.h"

#include <filesystem>

#include <QDate>
#include <QLabel>
#include <QMap>
#include <QMenu>
#include <QPushButton>
#include <QTreeWidget>
#include <QVBoxLayout>

#include "core/store/StudyStore.h"

namespace lucent {

StoreBrowser::StoreBrowser(QWidget* parent)
    : QWidget(parent), tree_(new QTreeWidget(this)), status_(new QLabel(this)) {
    tree_->setObjectName(QStringLiteral("storeTree"));
    tree_->setHeaderLabels(
        {tr("Patient / study / series"), tr("Date"), tr("Modality"), tr("Images"), tr("State")});
    status_->setWordWrap(true);
    auto* reload = new QPushButton(tr("Re&load"), this);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(tree_, 1);
    layout->addWidget(status_);
    layout->addWidget(reload, 0, Qt::AlignRight);
    connect(reload, &QPushButton::clicked, this, &StoreBrowser::refresh);
    tree_->setContextMenuPolicy(Qt::CustomContextMenu);
    connect(tree_, &QWidget::customContextMenuRequested, this, [this](const QPoint& at) {
        QTreeWidgetItem* item = tree_->itemAt(at);
        if (item == nullptr) {
            return;
        }
        QMenu menu;
        fillContextMenu(menu, item);
        menu.exec(tree_->viewport()->mapToGlobal(at));
    });
    connect(tree_, &QTreeWidget::itemDoubleClicked, this, [this](QTreeWidgetItem* item) {
        const QString folder = item->data(0, kFolderRole).toString();
        if (!folder.isEmpty()) {
            emit openSeries(folder, item->data(0, kSeriesUidRole).toString());
        }
    });
}

QStringList StoreBrowser::seriesFolders(const QTreeWidgetItem* item) {
    const QString own = item->data(0, kFolderRole).toString();
    if (!own.isEmpty()) {
        return {own};
    }
    QStringList out;
    for (int k = 0; k < item->childCount(); ++k) {
        out << seriesFolders(item->child(k));
    }
    return out;
}

void StoreBrowser::fillContextMenu(QMenu& menu, QTreeWidgetItem* item) {
    const QStringList folders = seriesFolders(item);
    const QString label = item->text(0);
    if (nodeNames_.isEmpty()) {
        menu.addAction(tr("Send to PACS (no node configured)"))->setEnabled(false);
    }
    for (int k = 0; k < nodeNames_.size(); ++k) {
        QAction* send = menu.addAction(tr("Send to %1").arg(nodeNames_[k]));
        send->setObjectName(QStringLiteral("sendTo%1").arg(k));
        connect(send, &QAction::triggered, this,
                [this, k, folders, label] { emit sendRequested(k, folders, label); });
    }
    menu.addSeparator();
    QAction* exporting = menu.addAction(tr("&Export..."));
    exporting->setObjectName(QStringLiteral("export"));
    connect(exporting, &QAction::triggered, this,
            [this, folders, label] { emit exportRequested(folders, label); });
}

void StoreBrowser::setStoreFolder(const QString& folder) {
    folder_ = folder;
    refresh();
}

void StoreBrowser::refresh() {
    tree_->clear();
    if (folder_.isEmpty() || !std::filesystem::exists(folder_.toStdString())) {
        status_->setText(tr("The store %1 is empty.").arg(folder_));
        return;
    }
    std::vector<StoredSeries> all;
    try {
        StudyStore store(folder_.toStdString());
        all = store.listSeries();
    } catch (const StoreError& e) {
        status_->setText(QString::fromStdString(e.what()));
        return;
    }
    QMap<QString, QTreeWidgetItem*> patients;
    QMap<QString, QTreeWidgetItem*> studies;
    for (const StoredSeries& s : all) {
        const QString patientKey =
            QString::fromStdString(s.info.patientId + "|" + s.info.patientName);
        QTreeWidgetItem*& patient = patients[patientKey];
        if (patient == nullptr) {
            patient = new QTreeWidgetItem(tree_);
            patient->setText(0, QString::fromStdString(s.info.patientName) + " (" +
                                    QString::fromStdString(s.info.patientId) + ")");
            patient->setExpanded(true);
        }
        const QString studyUid = QString::fromStdString(s.info.studyUid);
        QTreeWidgetItem*& study = studies[studyUid];
        if (study == nullptr) {
            study = new QTreeWidgetItem(patient);
            study->setText(0, s.studyDescription.empty()
                                  ? studyUid
                                  : QString::fromStdString(s.studyDescription));
            const QDate d = QDate::fromString(QString::fromStdString(s.info.studyDate),
                                              QStringLiteral("yyyyMMdd"));
            study->setText(1, d.isValid() ? d.toString(Qt::ISODate)
                                          : QString::fromStdString(s.info.studyDate));
            study->setExpanded(true);
        }
        auto* item = new QTreeWidgetItem(study);
        item->setText(
            0,
            tr("Series %1 %2").arg(s.seriesNumber).arg(QString::fromStdString(s.info.description)));
        item->setText(2, QString::fromStdString(s.info.modality));
        item->setText(3, s.expected > 0 ? QStringLiteral("%1/%2").arg(s.stored).arg(s.expected)
                                        : QString::number(s.stored));
        item->setText(4, s.complete ? tr("complete")
                                    : (s.expected > 0 ? tr("incomplete") : tr("received")));
        item->setData(0, kFolderRole, QString::fromStdString(s.folder.string()));
        item->setData(0, kSeriesUidRole, QString::fromStdString(s.info.seriesUid));
    }
    status_->setText(tr("%n series in %1", nullptr, static_cast<int>(all.size())).arg(folder_));
}

} // namespace lucent
