#include "ui/common/BackgroundExportDialog.h"

#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>

namespace lucent {

BackgroundExportDialog::BackgroundExportDialog(QWidget* parent) : QDialog(parent) {}

BackgroundExportDialog::~BackgroundExportDialog() {
    worker_.request_stop();
}

void BackgroundExportDialog::addExportRows(QFormLayout* form) {
    bar_ = new QProgressBar(this);
    status_ = new QLabel(this);
    export_ = new QPushButton(tr("&Export"), this);
    close_ = new QPushButton(tr("Close"), this);
    status_->setObjectName(QStringLiteral("status"));
    status_->setWordWrap(true);
    export_->setObjectName(QStringLiteral("exportButton"));
    export_->setDefault(true);
    form->addRow(bar_);
    form->addRow(status_);
    auto* buttons = new QHBoxLayout;
    buttons->addStretch(1);
    buttons->addWidget(export_);
    buttons->addWidget(close_);
    form->addRow(buttons);
    connect(export_, &QPushButton::clicked, this, [this] {
        if (!running_) {
            start();
        }
    });
    connect(close_, &QPushButton::clicked, this, [this] {
        if (running_) {
            worker_.request_stop();
            status_->setText(tr("Cancelling..."));
        } else {
            reject();
        }
    });
}

void BackgroundExportDialog::begin(const QString& doing) {
    running_ = true;
    export_->setEnabled(false);
    close_->setText(tr("Cancel"));
    status_->setText(doing);
    bar_->setRange(0, 0); // busy until the job's first report
}

void BackgroundExportDialog::reportProgress(int done, int total) {
    QMetaObject::invokeMethod(
        this,
        [this, done, total] {
            bar_->setRange(0, total);
            bar_->setValue(done);
            emit progressed(done, total);
        },
        Qt::QueuedConnection);
}

void BackgroundExportDialog::reportOutcome(ExportOutcome outcome) {
    QMetaObject::invokeMethod(
        this, [this, outcome = std::move(outcome)] { done(outcome); }, Qt::QueuedConnection);
}

void BackgroundExportDialog::done(const ExportOutcome& outcome) {
    running_ = false;
    worker_.join();
    export_->setEnabled(true);
    close_->setText(tr("Close"));
    status_->setText(outcome.message);
    if (!outcome.ok) {
        bar_->setRange(0, 1);
        bar_->setValue(0);
    }
    emit exportFinished(outcome.ok, outcome.message);
}

} // namespace lucent
