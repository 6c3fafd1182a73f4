#include "ui/pacs/PacsNodeSettings.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPushButton>
#include <QSettings>
#include <QSpinBox>
#include <QVBoxLayout>

#include "core/pacs/PacsService.h"
#include "ui/theme/Theme.h"

namespace lucent {
namespace {

QSpinBox* portBox(QWidget* parent) {
    auto* box = new QSpinBox(parent);
    box->setRange(1, 65535);
    return box;
}

} // namespace

PacsNodeSettings::PacsNodeSettings(PacsService* service, QSettings* settings, QWidget* parent)
    : QDialog(parent), service_(service), settings_(settings), list_(new QListWidget(this)),
      name_(new QLineEdit(this)), aeTitle_(new QLineEdit(this)), host_(new QLineEdit(this)),
      port_(portBox(this)), method_(new QComboBox(this)), dicomWebUrl_(new QLineEdit(this)),
      echo_(new QPushButton(tr("&Echo"), this)), echoResult_(new QLabel(this)),
      ourAeTitle_(new QLineEdit(this)), storagePort_(portBox(this)),
      storeFolder_(new QLineEdit(this)), timeout_(new QSpinBox(this)), error_(new QLabel(this)) {
    setWindowTitle(tr("PACS nodes"));
    const PacsConfig config = PacsConfig::load(*settings_);
    nodes_ = config.nodes;
    for (const auto& [widget, name] :
         std::initializer_list<std::pair<QWidget*, const char*>>{{list_, "nodes"},
                                                                 {name_, "name"},
                                                                 {aeTitle_, "aeTitle"},
                                                                 {host_, "host"},
                                                                 {port_, "port"},
                                                                 {method_, "method"},
                                                                 {dicomWebUrl_, "dicomWebUrl"},
                                                                 {echo_, "echo"},
                                                                 {echoResult_, "echoResult"},
                                                                 {ourAeTitle_, "ourAeTitle"},
                                                                 {storagePort_, "storagePort"},
                                                                 {storeFolder_, "storeFolder"},
                                                                 {timeout_, "timeout"},
                                                                 {error_, "error"}}) {
        widget->setObjectName(QString::fromLatin1(name));
    }
    method_->addItem(tr("C-GET"), methodKey(RetrievalMethod::CGet));
    method_->addItem(tr("C-MOVE (to Lucent's storage SCP)"), methodKey(RetrievalMethod::CMove));
    method_->addItem(tr("WADO-RS (DICOMweb)"), methodKey(RetrievalMethod::Wado));
    dicomWebUrl_->setPlaceholderText(QStringLiteral("http://host:8042/dicom-web"));
    echoResult_->setWordWrap(true);
    echoResult_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    error_->setWordWrap(true);
    error_->setStyleSheet(statusStyleSheet(StatusTone::Error));
    ourAeTitle_->setText(config.callingAeTitle);
    storagePort_->setValue(config.storagePort);
    storeFolder_->setText(config.storeFolder);
    timeout_->setRange(1, 600);
    timeout_->setSuffix(QStringLiteral(" s"));
    timeout_->setValue(config.timeoutSeconds);

    auto* add = new QPushButton(tr("&Add"), this);
    auto* remove = new QPushButton(tr("Re&move"), this);
    auto* left = new QVBoxLayout;
    left->addWidget(list_);
    auto* listButtons = new QHBoxLayout;
    listButtons->addWidget(add);
    listButtons->addWidget(remove);
    left->addLayout(listButtons);
    auto* nodeForm = new QFormLayout;
    nodeForm->addRow(tr("Name"), name_);
    nodeForm->addRow(tr("AE title"), aeTitle_);
    nodeForm->addRow(tr("Host"), host_);
    nodeForm->addRow(tr("Port"), port_);
    nodeForm->addRow(tr("Retrieval"), method_);
    nodeForm->addRow(tr("DICOMweb URL"), dicomWebUrl_);
    nodeForm->addRow(echo_, echoResult_);
    auto* top = new QHBoxLayout;
    top->addLayout(left);
    top->addLayout(nodeForm, 1);
    auto* lucentBox = new QGroupBox(tr("Lucent"), this);
    auto* lucentForm = new QFormLayout(lucentBox);
    lucentForm->addRow(tr("Our AE title"), ourAeTitle_);
    lucentForm->addRow(tr("Storage SCP port"), storagePort_);
    lucentForm->addRow(tr("Store folder"), storeFolder_);
    lucentForm->addRow(tr("Timeout"), timeout_);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Save | QDialogButtonBox::Close, this);
    auto* layout = new QVBoxLayout(this);
    layout->addLayout(top);
    layout->addWidget(lucentBox);
    layout->addWidget(error_);
    layout->addWidget(buttons);

    for (const PacsNodeConfig& n : nodes_) {
        list_->addItem(n.name);
    }
    connect(list_, &QListWidget::currentRowChanged, this, &PacsNodeSettings::loadNode);
    connect(add, &QPushButton::clicked, this, &PacsNodeSettings::addNode);
    connect(remove, &QPushButton::clicked, this, &PacsNodeSettings::removeNode);
    connect(echo_, &QPushButton::clicked, this, &PacsNodeSettings::echoCurrent);
    connect(name_, &QLineEdit::textEdited, this, [this](const QString& text) {
        if (QListWidgetItem* item = list_->item(current_)) {
            item->setText(text);
        }
    });
    connect(buttons, &QDialogButtonBox::accepted, this, [this] {
        if (save()) {
            accept();
        }
    });
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(service_, &PacsService::echoFinished, this, [this](bool ok, const QString& message) {
        echo_->setEnabled(true);
        echoResult_->setStyleSheet(statusStyleSheet(ok ? StatusTone::Ok : StatusTone::Error));
        echoResult_->setText((ok ? tr("OK: ") : tr("Failed: ")) + message);
    });
    loadNode(nodes_.isEmpty() ? -1 : 0);
    list_->setCurrentRow(current_);
}

void PacsNodeSettings::loadNode(int row) {
    storeNode();
    current_ = row >= 0 && row < nodes_.size() ? row : -1;
    const PacsNodeConfig n = current_ >= 0 ? nodes_[current_] : PacsNodeConfig{};
    for (QWidget* w : std::initializer_list<QWidget*>{name_, aeTitle_, host_, port_, method_,
                                                      dicomWebUrl_, echo_}) {
        w->setEnabled(current_ >= 0);
    }
    name_->setText(n.name);
    aeTitle_->setText(n.aeTitle);
    host_->setText(n.host);
    port_->setValue(n.port);
    method_->setCurrentIndex(method_->findData(methodKey(n.method)));
    dicomWebUrl_->setText(n.dicomWebUrl);
    echoResult_->clear();
}

void PacsNodeSettings::storeNode() {
    if (current_ < 0 || current_ >= nodes_.size()) {
        return;
    }
    PacsNodeConfig& n = nodes_[current_];
    n.name = name_->text().trimmed();
    n.aeTitle = aeTitle_->text().trimmed();
    n.host = host_->text().trimmed();
    n.port = port_->value();
    n.method = methodFromKey(method_->currentData().toString());
    n.dicomWebUrl = dicomWebUrl_->text().trimmed();
}

PacsConfig PacsNodeSettings::config() {
    storeNode(); // the form holds the latest edits
    PacsConfig c;
    c.nodes = nodes_;
    c.callingAeTitle = ourAeTitle_->text().trimmed();
    c.storagePort = storagePort_->value();
    c.storeFolder = storeFolder_->text().trimmed();
    c.timeoutSeconds = timeout_->value();
    return c;
}

bool PacsNodeSettings::save() {
    const PacsConfig c = config();
    if (const QString problem = c.validate(); !problem.isEmpty()) {
        error_->setText(problem);
        return false;
    }
    c.save(*settings_);
    error_->clear();
    emit saved(c);
    return true;
}

void PacsNodeSettings::addNode() {
    storeNode();
    PacsNodeConfig n;
    n.name = tr("PACS %1").arg(nodes_.size() + 1);
    n.aeTitle = QStringLiteral("ANY-SCP");
    n.host = QStringLiteral("localhost");
    nodes_ << n;
    list_->addItem(n.name);
    current_ = -1; // just stored
    list_->setCurrentRow(static_cast<int>(nodes_.size()) - 1);
}

void PacsNodeSettings::removeNode() {
    const int row = current_;
    if (row < 0) {
        return;
    }
    current_ = -1;
    nodes_.removeAt(row);
    delete list_->takeItem(row);
    loadNode(list_->currentRow());
}

void PacsNodeSettings::echoCurrent() {
    storeNode();
    if (current_ < 0) {
        return;
    }
    const PacsNodeConfig& n = nodes_[current_];
    if (const QString problem = n.validate(); !problem.isEmpty()) {
        echoResult_->setStyleSheet(statusStyleSheet(StatusTone::Error));
        echoResult_->setText(tr("Failed: ") + problem);
        return;
    }
    PacsConfig c = config();
    c.nodes.clear(); // only our identity and timeout matter for an echo
    if (c.validate().isEmpty()) {
        service_->setConfig(c);
    }
    echo_->setEnabled(false);
    echoResult_->setStyleSheet({});
    echoResult_->setText(tr("Echo %1...").arg(n.name));
    service_->echo(n);
}

} // namespace lucent
