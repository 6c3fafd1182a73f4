#pragma once
// Export of stored series to a new folder or ZIP file, de-identified or not,
// with or without a DICOMDIR (core/exchange/DicomExport), on a thread of its
// own with progress and cancel (BackgroundExportDialog). Non-modal: the reader
// can go on reading.

#include <QStringList>

#include "ui/common/BackgroundExportDialog.h"

class QCheckBox;
class QLineEdit;

namespace lucent {

class ExportDialog : public BackgroundExportDialog {
    Q_OBJECT

public:
    ExportDialog(const QStringList& seriesFolders, const QString& label, QWidget* parent = nullptr);

    QLineEdit* output() const { return output_; }
    QCheckBox* anonymize() const { return anonymize_; }
    QCheckBox* dicomdir() const { return dicomdir_; }

private:
    void browse();
    void start() override;

    QStringList folders_;
    QLineEdit* output_;
    QCheckBox* anonymize_;
    QCheckBox* dicomdir_;
};

} // namespace lucent
