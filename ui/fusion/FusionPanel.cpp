#include "ui/fusion/FusionPanel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QSlider>
#include <QSpinBox>

#include "core/fusion/FusionStyle.h"
#include "ui/fusion/ViewportFusion.h"
#include "ui/viewports/SeriesLibrary.h"
#include "ui/viewports/SeriesSession.h"
#include "ui/viewports/Viewport.h"
#include "ui/viewports/ViewportGrid.h"
#include "ui/viewports/ViewportWorkspace.h"

namespace lucent {
namespace {

QSlider* percentSlider(int value) {
    auto* slider = new QSlider(Qt::Horizontal);
    slider->setRange(0, 100);
    slider->setValue(value);
    return slider;
}

QDoubleSpinBox* windowBox() {
    auto* box = new QDoubleSpinBox;
    box->setRange(-1e7, 1e7);
    box->setDecimals(3);
    box->setKeyboardTracking(false);
    return box;
}

} // namespace

FusionPanel::FusionPanel(ViewportWorkspace* workspace, ViewportFusion* fusion, QWidget* parent)
    : QWidget(parent), workspace_(workspace), fusion_(fusion), overlay_(new QComboBox),
      colourMap_(new QComboBox), mode_(new QComboBox), opacity_(percentSlider(50)),
      checker_(new QSpinBox), swipe_(percentSlider(50)), center_(windowBox()), width_(windowBox()),
      clearBelow_(new QCheckBox(tr("Base shows below the window"))),
      nudge_(new QCheckBox(tr("Nudge the overlay by hand"))), status_(new QLabel) {
    nudge_->setToolTip(tr("Drag moves the overlay, Shift+drag turns it about the crosshair, "
                          "arrows move it 1 mm, Ctrl+Left/Right turn it 1 degree; each nudge "
                          "is kept as the pair's registration."));
    for (const FusionColourMap map : kFusionColourMaps) {
        colourMap_->addItem(tr(colourMapTitle(map)), static_cast<int>(map));
    }
    mode_->addItem(tr("Blend"), static_cast<int>(FusionMode::Blend));
    mode_->addItem(tr("Checkerboard"), static_cast<int>(FusionMode::Checkerboard));
    mode_->addItem(tr("Swipe"), static_cast<int>(FusionMode::Swipe));
    checker_->setRange(4, 512);
    checker_->setSuffix(tr(" px"));
    width_->setMinimum(1e-6);
    status_->setWordWrap(true);

    auto* form = new QFormLayout(this);
    form->addRow(tr("Overlay"), overlay_);
    form->addRow(tr("Colour map"), colourMap_);
    form->addRow(tr("Mode"), mode_);
    form->addRow(tr("Opacity"), opacity_);
    form->addRow(tr("Squares"), checker_);
    form->addRow(tr("Swipe line"), swipe_);
    form->addRow(tr("Window centre"), center_);
    form->addRow(tr("Window width"), width_);
    form->addRow(clearBelow_);
    form->addRow(nudge_);
    form->addRow(status_);

    connect(overlay_, &QComboBox::activated, this, &FusionPanel::overlayChosen);
    for (QComboBox* box : {colourMap_, mode_}) {
        connect(box, &QComboBox::currentIndexChanged, this, &FusionPanel::styleEdited);
    }
    for (QSlider* slider : {opacity_, swipe_}) {
        connect(slider, &QSlider::valueChanged, this, &FusionPanel::styleEdited);
    }
    connect(checker_, &QSpinBox::valueChanged, this, &FusionPanel::styleEdited);
    for (QDoubleSpinBox* box : {center_, width_}) {
        connect(box, &QDoubleSpinBox::valueChanged, this, &FusionPanel::styleEdited);
    }
    connect(clearBelow_, &QCheckBox::toggled, this, &FusionPanel::styleEdited);
    connect(nudge_, &QCheckBox::toggled, fusion, &ViewportFusion::setNudging);
    connect(workspace->grid(), &ViewportGrid::activeViewportChanged, this, &FusionPanel::refresh);
    connect(workspace->grid(), &ViewportGrid::viewportContentChanged, this, &FusionPanel::refresh);
    connect(workspace->library(), &SeriesLibrary::ready, this, &FusionPanel::refresh);
    connect(fusion, &ViewportFusion::fusionChanged, this, &FusionPanel::refresh);
    refresh();
}

Viewport* FusionPanel::active() const {
    return workspace_->grid()->activeViewport();
}

void FusionPanel::refresh() {
    updating_ = true;
    Viewport* viewport = active();
    SeriesSession* base = viewport != nullptr ? viewport->session() : nullptr;
    SeriesSession* current = viewport != nullptr ? fusion_->overlayOf(viewport) : nullptr;
    overlay_->clear();
    overlay_->addItem(tr("None"));
    for (SeriesSession* session : workspace_->library()->sessions()) {
        if (session->volume() && (base == nullptr || session->volume() != base->volume())) {
            overlay_->addItem(session->title(), QVariant::fromValue<QObject*>(session));
            if (session == current) {
                overlay_->setCurrentIndex(overlay_->count() - 1);
            }
        }
    }
    const std::optional<FusionStyle> style =
        viewport != nullptr ? fusion_->styleOf(viewport) : std::nullopt;
    for (QWidget* w : std::initializer_list<QWidget*>{colourMap_, mode_, opacity_, checker_, swipe_,
                                                      center_, width_, clearBelow_}) {
        w->setEnabled(style.has_value());
    }
    if (style) {
        showStyle(*style);
    }
    updating_ = false;
}

void FusionPanel::showStyle(const FusionStyle& style) {
    colourMap_->setCurrentIndex(colourMap_->findData(static_cast<int>(style.colourMap)));
    mode_->setCurrentIndex(mode_->findData(static_cast<int>(style.mode)));
    opacity_->setValue(static_cast<int>(std::lround(style.opacity * 100.0)));
    checker_->setValue(style.checkerPixels);
    swipe_->setValue(static_cast<int>(std::lround(style.swipe * 100.0)));
    center_->setSingleStep(std::max(style.width / 100.0, 1e-3));
    width_->setSingleStep(std::max(style.width / 100.0, 1e-3));
    center_->setValue(style.center);
    width_->setValue(style.width);
    clearBelow_->setChecked(style.clearBelowWindow);
}

void FusionPanel::overlayChosen(int index) {
    Viewport* viewport = active();
    if (viewport == nullptr) {
        return;
    }
    auto* session = qobject_cast<SeriesSession*>(overlay_->itemData(index).value<QObject*>());
    if (session == nullptr) {
        fusion_->clear(viewport);
        message_.clear();
    } else if (!fusion_->fuse(viewport, session, &message_)) {
        emit message(message_, 10000);
        refresh();
    } else {
        message_.clear();
    }
    status_->setText(message_);
}

void FusionPanel::styleEdited() {
    Viewport* viewport = active();
    if (updating_ || viewport == nullptr || !fusion_->styleOf(viewport)) {
        return;
    }
    FusionStyle style = *fusion_->styleOf(viewport);
    style.colourMap = static_cast<FusionColourMap>(colourMap_->currentData().toInt());
    style.mode = static_cast<FusionMode>(mode_->currentData().toInt());
    style.opacity = opacity_->value() / 100.0;
    style.checkerPixels = checker_->value();
    style.swipe = swipe_->value() / 100.0;
    style.center = center_->value();
    style.width = width_->value();
    style.clearBelowWindow = clearBelow_->isChecked();
    updating_ = true; // fusionChanged refreshes the controls with what they show already
    fusion_->setStyle(viewport, style);
    updating_ = false;
}

} // namespace lucent
