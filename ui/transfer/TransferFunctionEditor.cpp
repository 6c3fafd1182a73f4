#include "ui/transfer/TransferFunctionEditor.h"

#include <QComboBox>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QInputDialog>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QStandardPaths>
#include <QVBoxLayout>

#include "core/tf/VolumeHistogram.h"
#include "ui/theme/Theme.h"
#include "ui/transfer/TransferFunctionCanvas.h"

namespace lucent {

namespace {

constexpr int kHistogramBins = 256;

std::filesystem::path toPath(const QString& s) {
    return std::filesystem::path(s.toStdString());
}

} // namespace

TransferFunctionEditor::TransferFunctionEditor(QWidget* parent) : QWidget(parent) {
    canvas_ = new TransferFunctionCanvas(this);
    presets_ = new QComboBox(this);
    presets_->setToolTip(tr("Transfer-function presets (built-in and your own)"));
    auto* save = new QPushButton(tr("Save preset…"), this);
    auto* open = new QPushButton(tr("Open…"), this);
    auto* exportButton = new QPushButton(tr("Export…"), this);
    status_ = new QLabel(this);
    status_->setWordWrap(true);

    auto* bar = new QHBoxLayout;
    bar->addWidget(presets_, 1);
    bar->addWidget(save);
    bar->addWidget(open);
    bar->addWidget(exportButton);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(4, 4, 4, 4);
    layout->addLayout(bar);
    layout->addWidget(canvas_, 1);
    layout->addWidget(status_);

    connect(canvas_, &TransferFunctionCanvas::transferFunctionChanged, this,
            &TransferFunctionEditor::transferFunctionChanged);
    connect(presets_, &QComboBox::activated, this,
            [this](int index) { loadPresetNamed(presets_->itemText(index)); });
    connect(save, &QPushButton::clicked, this, &TransferFunctionEditor::askAndSavePreset);
    connect(open, &QPushButton::clicked, this, &TransferFunctionEditor::openFile);
    connect(exportButton, &QPushButton::clicked, this, &TransferFunctionEditor::exportFile);
    refreshPresetList();
}

std::filesystem::path TransferFunctionEditor::userPresetDirectory() {
    return toPath(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation)) / "presets";
}

void TransferFunctionEditor::setVolume(std::shared_ptr<const Volume> volume) {
    canvas_->setHistogram(volume ? computeHistogram(*volume, kHistogramBins) : VolumeHistogram{});
}

const TransferFunction& TransferFunctionEditor::transferFunction() const {
    return canvas_->transferFunction();
}

void TransferFunctionEditor::setTransferFunction(const TransferFunction& tf) {
    if (tf == canvas_->transferFunction()) {
        return; // an echo of our own edit: keep the drag going
    }
    canvas_->setTransferFunction(tf);
    const int index = presets_->findText(QString::fromStdString(tf.name));
    const QSignalBlocker blocker(presets_);
    presets_->setCurrentIndex(index);
}

void TransferFunctionEditor::refreshPresetList() {
    const QString current = presets_->currentText();
    QStringList names;
    for (const auto& name : presetNames()) {
        names << QString::fromStdString(name);
    }
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(userPresetDirectory(), ec)) {
        if (entry.path().extension() == ".json") {
            names << QString::fromStdString(entry.path().stem().string());
        }
    }
    names.removeDuplicates();
    names.sort();
    const QSignalBlocker blocker(presets_);
    presets_->clear();
    presets_->addItems(names);
    presets_->setCurrentIndex(presets_->findText(current));
}

bool TransferFunctionEditor::loadPresetNamed(const QString& name) {
    try {
        const auto user = userPresetDirectory() / (name.toStdString() + ".json");
        std::error_code ec;
        applyLoaded(std::filesystem::exists(user, ec) ? readTransferFunction(user)
                                                      : loadPreset(name.toStdString()),
                    name);
        return true;
    } catch (const std::exception& e) {
        showStatus(QString::fromStdString(e.what()), true);
        return false;
    }
}

void TransferFunctionEditor::applyLoaded(const TransferFunction& tf, const QString& source) {
    canvas_->setTransferFunction(tf);
    const QSignalBlocker blocker(presets_);
    presets_->setCurrentIndex(presets_->findText(QString::fromStdString(tf.name)));
    showStatus(tr("Loaded %1").arg(source), false);
    emit transferFunctionChanged(canvas_->transferFunction());
}

bool TransferFunctionEditor::saveUserPreset(const QString& name) {
    const QString trimmed = name.trimmed();
    if (trimmed.isEmpty() || trimmed.contains('/') || trimmed.contains('\\') ||
        trimmed.startsWith('.')) {
        showStatus(tr("A preset name must be a plain file name: \"%1\"").arg(name), true);
        return false;
    }
    try {
        std::filesystem::create_directories(userPresetDirectory());
        TransferFunction tf = canvas_->transferFunction();
        tf.name = trimmed.toStdString();
        const auto path = userPresetDirectory() / (tf.name + ".json");
        writeTransferFunction(tf, path);
        canvas_->setTransferFunction(tf);
        refreshPresetList();
        presets_->setCurrentIndex(presets_->findText(trimmed));
        showStatus(tr("Saved %1").arg(QString::fromStdString(path.string())), false);
        return true;
    } catch (const std::exception& e) {
        showStatus(QString::fromStdString(e.what()), true);
        return false;
    }
}

void TransferFunctionEditor::askAndSavePreset() {
    bool ok = false;
    const QString name =
        QInputDialog::getText(this, tr("Save preset"), tr("Preset name:"), QLineEdit::Normal,
                              QString::fromStdString(transferFunction().name), &ok);
    if (ok) {
        saveUserPreset(name);
    }
}

void TransferFunctionEditor::openFile() {
    const QString file = QFileDialog::getOpenFileName(this, tr("Open transfer function"), {},
                                                      tr("Transfer functions (*.json)"));
    if (file.isEmpty()) {
        return;
    }
    try {
        applyLoaded(readTransferFunction(toPath(file)), file);
    } catch (const std::exception& e) {
        showStatus(QString::fromStdString(e.what()), true);
    }
}

void TransferFunctionEditor::exportFile() {
    const QString file = QFileDialog::getSaveFileName(this, tr("Export transfer function"), {},
                                                      tr("Transfer functions (*.json)"));
    if (file.isEmpty()) {
        return;
    }
    try {
        writeTransferFunction(transferFunction(), toPath(file));
        showStatus(tr("Saved %1").arg(file), false);
    } catch (const std::exception& e) {
        showStatus(QString::fromStdString(e.what()), true);
    }
}

void TransferFunctionEditor::showStatus(const QString& text, bool error) {
    status_->setText(text);
    status_->setStyleSheet(error ? statusStyleSheet(StatusTone::Error) : QString());
}

} // namespace lucent
