#pragma once

#include <filesystem>
#include <memory>

#include <QString>
#include <QWidget>

#include "core/tf/TransferFunction.h"
#include "core/volume/Volume.h"

class QComboBox;
class QLabel;

namespace lucent {

class TransferFunctionCanvas;

// The transfer-function editor: the canvas (histogram, opacity points, colour
// stops), a preset picker over the built-in presets (core's presetNames()) and
// the user's own (userPresetDirectory()), and buttons to save the current
// function as a user preset and to open or export a JSON file.
// transferFunctionChanged is emitted for every user edit, while dragging too,
// and when a preset or file is loaded; setTransferFunction does not emit.
class TransferFunctionEditor : public QWidget {
    Q_OBJECT

public:
    explicit TransferFunctionEditor(QWidget* parent = nullptr);

    // Computes the volume's histogram (256 bins) for the background.
    void setVolume(std::shared_ptr<const Volume> volume);
    const TransferFunction& transferFunction() const;
    TransferFunctionCanvas* canvas() const { return canvas_; }

    // <AppDataLocation>/presets: where "Save preset" writes <name>.json.
    static std::filesystem::path userPresetDirectory();

public slots:
    void setTransferFunction(const lucent::TransferFunction& tf);
    // A built-in preset name or a user preset's name (user presets win). Emits.
    // Returns false (and says why in the status line) when it cannot be read.
    bool loadPresetNamed(const QString& name);
    // Writes the current function to userPresetDirectory()/<name>.json and lists it.
    bool saveUserPreset(const QString& name);
    void refreshPresetList();

signals:
    void transferFunctionChanged(const lucent::TransferFunction& tf);

private:
    void applyLoaded(const TransferFunction& tf, const QString& source);
    void askAndSavePreset();
    void openFile();
    void exportFile();
    void showStatus(const QString& text, bool error);

    TransferFunctionCanvas* canvas_ = nullptr;
    QComboBox* presets_ = nullptr;
    QLabel* status_ = nullptr;
};

} // namespace lucent
