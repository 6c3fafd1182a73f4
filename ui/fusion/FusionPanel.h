#pragma once
// The Fusion dock: what the active viewport fuses over its series and how: the overlay
// (any other loaded volume), colour map, blend/checkerboard/swipe, opacity, the
// checkerboard's squares, the swipe line, the overlay's window, and whether values below
// the window leave the base alone.

#include <QWidget>

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QSlider;
class QSpinBox;

namespace lucent {

class Viewport;
class ViewportFusion;
class ViewportWorkspace;
struct FusionStyle;

class FusionPanel : public QWidget {
    Q_OBJECT

public:
    FusionPanel(ViewportWorkspace* workspace, ViewportFusion* fusion, QWidget* parent = nullptr);

    // Lists the loaded volumes again (after a load) and shows the active viewport's state.
    void refresh();

    // The controls, for tests and shortcuts.
    QComboBox* overlayChoice() const { return overlay_; }
    QComboBox* colourMapChoice() const { return colourMap_; }
    QComboBox* modeChoice() const { return mode_; }
    QSlider* opacitySlider() const { return opacity_; }
    QSlider* swipeSlider() const { return swipe_; }
    QDoubleSpinBox* windowCenter() const { return center_; }
    QDoubleSpinBox* windowWidth() const { return width_; }
    QCheckBox* nudgeSwitch() const { return nudge_; }
    const QString& lastMessage() const { return message_; }

signals:
    void message(const QString& text, int timeoutMs);

private:
    void overlayChosen(int index);
    void styleEdited();
    void showStyle(const FusionStyle& style);
    Viewport* active() const;

    ViewportWorkspace* workspace_;
    ViewportFusion* fusion_;
    QComboBox* overlay_;
    QComboBox* colourMap_;
    QComboBox* mode_;
    QSlider* opacity_;
    QSpinBox* checker_;
    QSlider* swipe_;
    QDoubleSpinBox* center_;
    QDoubleSpinBox* width_;
    QCheckBox* clearBelow_;
    QCheckBox* nudge_;
    QLabel* status_;
    QString message_;
    bool updating_ = false;
};

} // namespace lucent
