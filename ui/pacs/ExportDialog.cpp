#include "ui/pacs/ExportDialog.h"

#include <QCheckBox>
#include <QDir>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>

#include "core/exchange/DicomExport.h"

namespace lucent {

ExportDialog::ExportDialog(const QStringList& seriesFolders, const QString& label, QWidget* parent)
    : BackgroundExportDialog(parent), folders_(seriesFolders), output_(new QLineEdit(this)),
      anonymize_(
          new QCheckBox(tr("&De-identify (DICOM PS3.15 Basic Profile; pixels untouched)"), this)),
      dicomdir_(new QCheckBox(tr("Write a DICOM&DIR"), this)) {
    setWindowTitle(tr("Export %1").arg(label));
    output_->setObjectName(QStringLiteral("output"));
    output_->setPlaceholderText(tr("a new folder, or a file ending in .zip"));
    anonymize_->setObjectName(QStringLiteral("anonymize"));
    dicomdir_->setObjectName(QStringLiteral("dicomdir"));
    auto* browse = new QPushButton(tr("&Browse..."), this);
    auto* where = new QHBoxLayout;
    where->addWidget(output_, 1);
    where->addWidget(browse);
    auto* form = new QFormLayout(this);
    form->addRow(tr("Series"), new QLabel(tr("%n series", nullptr, int(folders_.size())), this));
    form->addRow(tr("To"), where);
    form->addRow(anonymize_);
    form->addRow(dicomdir_);
    addExportRows(form);
    connect(browse, &QPushButton::clicked, this, &ExportDialog::browse);
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
    if (output_->text().trimmed().isEmpty()) {
        status()->setText(tr("Give a new folder or a .zip file to export to."));
        return;
    }
    ExportOptions options;
    options.anonymize = anonymize_->isChecked();
    options.dicomdir = dicomdir_->isChecked();
    const std::string target = output_->text().trimmed().toStdString();
    startJob(tr("Exporting..."), [this, options, target,
                                  folders = folders_](std::stop_token stop) mutable {
        options.stop = stop;
        options.onProgress = [this](int doneFiles, int total) { reportProgress(doneFiles, total); };
        std::vector<InstanceHeader> instances;
        std::vector<std::string> passedOver;
        for (const QString& f : folders) {
            for (InstanceHeader& h : collectInstances(f.toStdString(), "", passedOver)) {
                instances.push_back(std::move(h));
            }
        }
        const ExportResult r = exportInstances(instances, target, options);
        return ExportOutcome{true, tr("%1 instance(s) exported%2 to %3")
                                       .arg(r.files)
                                       .arg(options.anonymize ? tr(", de-identified,") : QString())
                                       .arg(QString::fromStdString(r.output.string()))};
    });
}

} // namespace lucent
