#include "ui/pacs/StoreBrowser.h"

#include <filesystem>

#include <QDate>
#include <QLabel>
#include <QMap>
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
    connect(tree_, &QTreeWidget::itemDoubleClicked, this, [this](QTreeWidgetItem* item) {
        const QString folder = item->data(0, kFolderRole).toString();
        if (!folder.isEmpty()) {
            emit openSeries(folder, item->data(0, kSeriesUidRole).toString());
        }
    });
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
