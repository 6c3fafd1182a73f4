#include "ui/pacs/RetrievalProgress.h"

#include <QHBoxLayout>
#include <QHeaderView>
#include <QPushButton>
#include <QTreeWidget>
#include <QVBoxLayout>

#include "core/pacs/PacsService.h"
#include "ui/theme/Theme.h"

namespace lucent {

RetrievalProgress::RetrievalProgress(PacsService* service, QWidget* parent)
    : QWidget(parent), service_(service), list_(new QTreeWidget(this)),
      cancel_(new QPushButton(tr("Cancel retrievals"), this)) {
    list_->setObjectName(QStringLiteral("retrievalList"));
    list_->setHeaderLabels(
        {tr("Series"), tr("Completed"), tr("Remaining"), tr("Failed"), tr("Status")});
    list_->setRootIsDecorated(true); // a transfer's instances that were not stored, below it
    list_->header()->setSectionResizeMode(Series, QHeaderView::Stretch);
    cancel_->setObjectName(QStringLiteral("cancelRetrievals"));
    cancel_->setEnabled(false);
    auto* buttons = new QHBoxLayout;
    buttons->addStretch();
    buttons->addWidget(cancel_);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(list_);
    layout->addLayout(buttons);
    connect(cancel_, &QPushButton::clicked, this, [this] {
        service_->cancelRetrievals();
        cancel_->setEnabled(false);
    });
    connect(service_, &PacsService::retrievalQueued, this, &RetrievalProgress::queued);
    connect(service_, &PacsService::retrievalProgress, this, &RetrievalProgress::progress);
    connect(service_, &PacsService::retrievalFinished, this, &RetrievalProgress::finished);
    connect(service_, &PacsService::instanceNotStored, this,
            [this](const QString& key, const QString& file, const QString& message) {
                if (QTreeWidgetItem* parent = row(key)) {
                    auto* item = new QTreeWidgetItem(parent);
                    item->setText(Series, file);
                    item->setText(Status, message);
                    item->setToolTip(Status, message);
                    parent->setExpanded(true);
                }
            });
    connect(service_, &PacsService::allRetrievalsFinished, this,
            [this] { cancel_->setEnabled(false); });
}

QTreeWidgetItem* RetrievalProgress::row(const QString& seriesUid) const {
    for (int i = list_->topLevelItemCount() - 1; i >= 0; --i) {
        QTreeWidgetItem* item = list_->topLevelItem(i);
        if (item->data(Series, Qt::UserRole).toString() == seriesUid) {
            return item;
        }
    }
    return nullptr;
}

void RetrievalProgress::queued(const QString& seriesUid, const QString& label) {
    auto* item = new QTreeWidgetItem(list_);
    item->setText(Series, label.isEmpty() ? seriesUid : label);
    item->setToolTip(Series, seriesUid);
    item->setData(Series, Qt::UserRole, seriesUid);
    for (const Column c : {Completed, Remaining, Failed}) {
        item->setText(c, QStringLiteral("0"));
        item->setTextAlignment(c, Qt::AlignRight | Qt::AlignVCenter);
    }
    item->setText(Status, tr("queued"));
    list_->scrollToItem(item);
    cancel_->setEnabled(true);
}

void RetrievalProgress::progress(const QString& seriesUid, int completed, int remaining,
                                 int failed) {
    if (QTreeWidgetItem* item = row(seriesUid)) {
        item->setText(Completed, QString::number(completed));
        item->setText(Remaining, QString::number(remaining));
        item->setText(Failed, QString::number(failed));
        if (item->text(Status) == tr("queued")) {
            item->setText(Status, seriesUid.startsWith(QLatin1String("send-")) ? tr("sending")
                                                                               : tr("retrieving"));
        }
    }
}

void RetrievalProgress::finished(const QString& seriesUid, bool ok, const QString& message) {
    if (QTreeWidgetItem* item = row(seriesUid)) {
        item->setText(Status, message);
        item->setToolTip(Status, message);
        item->setForeground(Status, ok ? palette().text()
                                       : QBrush(statusColour(StatusTone::Error, palette())));
    }
}

} // namespace lucent
