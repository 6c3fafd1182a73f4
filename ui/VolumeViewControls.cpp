#include "ui/VolumeViewControls.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>

#include "ui/VolumeView.h"

namespace lucent {

namespace {

constexpr RenderMode kModes[] = {RenderMode::Dvr, RenderMode::Mip, RenderMode::MinIp,
                                 RenderMode::Average, RenderMode::Isosurface};
const char* const kModeLabels[] = {"DVR", "MIP", "MinIP", "Average", "Isosurface"};

} // namespace

VolumeViewControls::VolumeViewControls(VolumeView* view, QWidget* parent)
    : QWidget(parent), view_(view) {
    presets_ = new QComboBox(this);
    for (const auto& name : presetNames()) {
        presets_->addItem(QString::fromStdString(name));
    }
    modes_ = new QComboBox(this);
    for (const char* label : kModeLabels) {
        modes_->addItem(tr(label));
    }
    iso_ = new QDoubleSpinBox(this);
    iso_->setRange(-100000.0, 100000.0);
    iso_->setValue(view->isoValue());
    iso_->setEnabled(false);
    auto* reset = new QPushButton(tr("Reset view"), this);

    auto* form = new QFormLayout(this);
    form->setContentsMargins(4, 4, 4, 4);
    form->addRow(tr("Preset"), presets_);
    auto* modeRow = new QHBoxLayout;
    modeRow->addWidget(modes_, 1);
    modeRow->addWidget(iso_);
    form->addRow(tr("Mode"), modeRow);
    const char* const axes[] = {"Clip i", "Clip j", "Clip k"};
    for (int axis = 0; axis < 3; ++axis) {
        auto* row = new QHBoxLayout;
        for (int end = 0; end < 2; ++end) {
            auto* s = new QSlider(Qt::Horizontal, this);
            clip_[static_cast<std::size_t>(2 * axis + end)] = s;
            row->addWidget(s);
            connect(s, &QSlider::valueChanged, this, &VolumeViewControls::applyClip);
        }
        form->addRow(tr(axes[axis]), row);
    }
    form->addRow(reset);

    connect(presets_, &QComboBox::activated, this, [this](int index) {
        try {
            view_->setTransferFunction(loadPreset(presets_->itemText(index).toStdString()));
        } catch (const std::exception& e) {
            presets_->setToolTip(QString::fromStdString(e.what()));
        }
    });
    connect(view_, &VolumeView::transferFunctionChanged, this, [this](const TransferFunction& tf) {
        const QSignalBlocker blocker(presets_);
        presets_->setCurrentIndex(presets_->findText(QString::fromStdString(tf.name)));
    });
    connect(modes_, &QComboBox::currentIndexChanged, this, [this](int index) {
        const RenderMode mode = kModes[std::clamp(index, 0, 4)];
        iso_->setEnabled(mode == RenderMode::Isosurface);
        view_->setMode(mode);
    });
    connect(iso_, &QDoubleSpinBox::valueChanged, view_, &VolumeView::setIsoValue);
    connect(reset, &QPushButton::clicked, view_, &VolumeView::resetCamera);
    connect(view_, &VolumeView::volumeChanged, this, &VolumeViewControls::volumeChanged);
    volumeChanged();
}

QSlider* VolumeViewControls::clipSlider(int axis, int end) const {
    return clip_.at(static_cast<std::size_t>(2 * axis + end));
}

void VolumeViewControls::volumeChanged() {
    const auto& volume = view_->volume();
    const glm::ivec3 dims = volume ? volume->dims() : glm::ivec3(1);
    for (int axis = 0; axis < 3; ++axis) {
        for (int end = 0; end < 2; ++end) {
            QSlider* s = clipSlider(axis, end);
            const QSignalBlocker blocker(s);
            s->setRange(0, std::max(0, dims[axis] - 1));
            s->setValue(end == 0 ? 0 : dims[axis] - 1);
            s->setEnabled(volume != nullptr);
        }
    }
    const QSignalBlocker blocker(presets_);
    presets_->setCurrentIndex(
        presets_->findText(QString::fromStdString(view_->transferFunction().name)));
}

void VolumeViewControls::applyClip() {
    ClipBox clip;
    for (int axis = 0; axis < 3; ++axis) {
        const int first = clipSlider(axis, 0)->value();
        const int last = clipSlider(axis, 1)->value();
        clip.lo[axis] = std::min(first, last);
        clip.hi[axis] = std::max(first, last);
    }
    view_->setClipBox(clip);
}

} // namespace lucent
