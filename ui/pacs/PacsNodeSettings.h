#pragma once
// Settings for PACS: the nodes (name, AE title, host, port, retrieval method,
// DICOMweb URL) with an Echo button, and Lucent's own AE title, storage SCP
// port and store folder. Saved with QSettings.

#include <QDialog>

#include "core/pacs/PacsConfig.h"

class QComboBox;
class QLabel;
class QLineEdit;
class QListWidget;
class QPushButton;
class QSettings;
class QSpinBox;

namespace lucent {

class PacsService;

class PacsNodeSettings : public QDialog {
    Q_OBJECT

public:
    PacsNodeSettings(PacsService* service, QSettings* settings, QWidget* parent = nullptr);

    // The configuration as edited (nodes and Lucent's identity).
    PacsConfig config();
    // Validates, saves to the settings and says so; false (with the message
    // naming the field shown) when something is wrong.
    bool save();
    void addNode();
    void removeNode();
    void echoCurrent();
    QLabel* echoResult() const { return echoResult_; }
    QLabel* error() const { return error_; }

signals:
    void saved(const lucent::PacsConfig& config);

private:
    void loadNode(int row);
    void storeNode();

    PacsService* service_;
    QSettings* settings_;
    QList<PacsNodeConfig> nodes_;
    int current_ = -1;
    QListWidget* list_;
    QLineEdit* name_;
    QLineEdit* aeTitle_;
    QLineEdit* host_;
    QSpinBox* port_;
    QComboBox* method_;
    QLineEdit* dicomWebUrl_;
    QPushButton* echo_;
    QLabel* echoResult_;
    QLineEdit* ourAeTitle_;
    QSpinBox* storagePort_;
    QLineEdit* storeFolder_;
    QSpinBox* timeout_;
    QLabel* error_;
};

} // namespace lucent
