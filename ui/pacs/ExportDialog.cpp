#include "ui/pacs/ExportDialog.h"

#include <QCheckBox>
#include <QDir>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>

#include "core/exchange/DicomExport.h"

namespace lucent {

ExportDialog::ExportDialog(const QStringList& seriesFolders, const QString& label, QWidget* parent)
    : QDialog(parent), folders_(seriesFolders), output_(new QLineEdit(this)),
      anonymize_(
          new QCheckBox(tr("&De-identify (DICOM PS3.15 Basic Profile; pixels untouched)"), this)),
      dicomdir_(new QCheckBox(tr("Write a DICOM&DIR"), this)), bar_(new QProgressBar(this)),
      status_(new QLabel(this)), export_(new QPushButton(tr("&Export"), this)),
      close_(new QPushButton(tr("Close"), this)) {
    setWindowTitle(tr("Export %1").arg(label));
    output_->setObjectName(QStringLiteral("output"));
    output_->setPlaceholderText(tr("a new folder, or a file ending in .zip"));
    anonymize_->setObjectName(QStringLiteral("anonymize"));
    dicomdir_->setObjectName(QStringLiteral("dicomdir"));
    status_->setObjectName(QStringLiteral("status"));
    status_->setWordWrap(true);
    export_->setObjectName(QStringLiteral("exportButton"));
    export_->setDefault(true);
    auto* browse = new QPushButton(tr("&Browse..."), this);
    auto* where = new QHBoxLayout;
    where->addWidget(output_, 1);
    where->addWidget(browse);
    auto* form = new QFormLayout(this);
    form->addRow(tr("Series"), new QLabel(tr("%n series", nullptr, int(folders_.size())), this));
    form->addRow(tr("To"), where);
    form->addRow(anonymize_);
    form->addRow(dicomdir_);
    form->addRow(bar_);
    form->addRow(status_);
    auto* buttons = new QHBoxLayout;
    buttons->addStretch(1);
    buttons->addWidget(export_);
    buttons->addWidget(close_);
    form->addRow(buttons);
    connect(browse, &QPushButton::clicked, this, &ExportDialog::browse);
    connect(export_, &QPushButton::clicked, this, &ExportDialog::start);
    connect(close_, &QPushButton::clicked, this, [this] {
        if (running_) {
            worker_.request_stop();
        } else {
            reject();
        }
    });
}

ExportDialog::~ExportDialog() {
    worker_.request_stop();
}

void ExportDialog::browse() {
    const QString chosen = QFileDialog::getSaveFileName(
        this, tr("Export to"), QDir::homePath(), tr("Folder (no extension) (*);;ZIP file (*.zip)"),
        nullptr, QFileDialog::DontConfirmOverwrite);
    if (!chosen.isEmpty()) {
        output_->setText(chosen);
    }
}

void ExportDialog::start() {
    if (running_) {
        return;
    }
    if (output_->text().trimmed().isEmpty()) {
        status_->setText(tr("Give a new folder or a .zip file to export to."));
        return;
    }
    running_ = true;
    export_->setEnabled(false);
    close_->setText(tr("Cancel"));
    status_->setText(tr("Exporting..."));
    bar_->setValue(0);
    ExportOptions options;
    options.anonymize = anonymize_->isChecked();
    options.dicomdir = dicomdir_->isChecked();
    const std::string target = output_->text().trimmed().toStdString();
    worker_ =
        std::jthread([this, options, target, folders = folders_](std::stop_token stop) mutable {
            options.stop = stop;
            options.onProgress = [this](int doneFiles, int total) {
                QMetaObject::invokeMethod(
                    this,
                    [this, doneFiles, total] {
                        bar_->setRange(0, total);
                        bar_->setValue(doneFiles);
                    },
                    Qt::QueuedConnection);
            };
            bool ok = false;
            QString message;
            try {
                std::vector<InstanceHeader> instances;
                std::vector<std::string> passedOver;
                for (const QString& f : folders) {
                    for (InstanceHeader& h : collectInstances(f.toStdString(), "", passedOver)) {
                        instances.push_back(std::move(h));
                    }
                }
                const ExportResult r = exportInstances(instances, target, options);
                ok = true;
                message = tr("%1 instance(s) exported%2 to %3")
                              .arg(r.files)
                              .arg(options.anonymize ? tr(", de-identified,") : QString())
                              .arg(QString::fromStdString(r.output.string()));
            } catch (const std::exception& e) {
                message = QString::fromStdString(e.what());
            }
            QMetaObject::invokeMethod(
                this, [this, ok, message] { done(ok, message); }, Qt::QueuedConnection);
        });
}

void ExportDialog::done(bool ok, const QString& message) {
    running_ = false;
    worker_.join();
    export_->setEnabled(true);
    close_->setText(tr("Close"));
    status_->setText(message);
    emit exportFinished(ok, message);
}

} // namespace lucent
