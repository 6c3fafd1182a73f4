#pragma once
// Export of stored series to a new folder or ZIP file, de-identified or not,
// with or without a DICOMDIR (core/exchange/DicomExport), on a thread of its
// own with progress and cancel. Non-modal: the reader can go on reading.

#include <QDialog>
#include <QStringList>

#include <thread>

class QCheckBox;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;

namespace lucent {

class ExportDialog : public QDialog {
    Q_OBJECT

public:
    ExportDialog(const QStringList& seriesFolders, const QString& label, QWidget* parent = nullptr);
    ~ExportDialog() override; // cancels a running export and waits for it

    QLineEdit* output() const { return output_; }
    QCheckBox* anonymize() const { return anonymize_; }
    QCheckBox* dicomdir() const { return dicomdir_; }
    QPushButton* exportButton() const { return export_; }
    QLabel* status() const { return status_; }
    bool running() const { return worker_.joinable() && running_; }

signals:
    void exportFinished(bool ok, const QString& message);

private:
    void browse();
    void start();
    void done(bool ok, const QString& message);

    QStringList folders_;
    QLineEdit* output_;
    QCheckBox* anonymize_;
    QCheckBox* dicomdir_;
    QProgressBar* bar_;
    QLabel* status_;
    QPushButton* export_;
    QPushButton* close_;
    bool running_ = false;
    std::jthread worker_;
};

} // namespace lucent
