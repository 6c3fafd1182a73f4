#include "ui/segmentation/SegmentTools3d.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QPushButton>
#include <QSignalBlocker>
#include <QVBoxLayout>

#include "ui/segmentation/GrowFromSeedsEffect.h"
#include "ui/segmentation/MaskedRendering.h"
#include "ui/segmentation/Scissors3d.h"
#include "ui/segmentation/SegmentSurfaces3d.h"
#include "ui/segmentation/SegmentationSession.h"
#include "ui/segmentation/SegmentsPanel.h"
#include "ui/volume/VolumeView.h"

namespace lucent {

SegmentTools3d::SegmentTools3d(SegmentsPanel* panel, ViewFor viewFor, QWidget* parent)
    : QWidget(parent), panel_(panel), viewFor_(std::move(viewFor)),
      grow_(new GrowFromSeedsEffect(this)) {
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(makeScissorsBox());
    layout->addWidget(makeViewBox());
    layout->addWidget(makeGrowBox());
    connect(grow_, &GrowFromSeedsEffect::message, this, &SegmentTools3d::message);
}

SegmentTools3d::~SegmentTools3d() {
    delete scissors_.data();
}

Scissors3d* SegmentTools3d::scissors() const {
    return scissors_.data();
}

QWidget* SegmentTools3d::makeScissorsBox() {
    auto* box = new QGroupBox(tr("Scissors in the 3D view"), this);
    auto* form = new QFormLayout(box);
    shape_ = new QComboBox(box);
    shape_->addItem(tr("Freehand"), int(Scissors3d::Shape::Freehand));
    shape_->addItem(tr("Circle"), int(Scissors3d::Shape::Circle));
    shape_->addItem(tr("Rectangle"), int(Scissors3d::Shape::Rectangle));
    operation_ = new QComboBox(box);
    operation_->addItem(tr("Erase inside"), int(ScissorsOperation::EraseInside));
    operation_->addItem(tr("Erase outside"), int(ScissorsOperation::EraseOutside));
    operation_->addItem(tr("Fill inside"), int(ScissorsOperation::FillInside));
    operation_->addItem(tr("Fill outside"), int(ScissorsOperation::FillOutside));
    scissorsOn_ = new QPushButton(tr("Draw on the 3D view"), box);
    scissorsOn_->setCheckable(true);
    scissorsOn_->setToolTip(tr("Left-drag on the 3D view draws the shape; its release cuts the "
                               "active segment along the view's rays (one undo step)"));
    form->addRow(tr("Shape"), shape_);
    form->addRow(tr("Cut"), operation_);
    form->addRow(scissorsOn_);
    connect(scissorsOn_, &QPushButton::toggled, this, [this](bool on) {
        if (!setScissors(on) && on) {
            scissorsOn_->setChecked(false);
        }
    });
    const auto follow = [this] {
        if (scissors_) {
            scissors_->setShape(Scissors3d::Shape(shape_->currentData().toInt()));
            scissors_->setOperation(ScissorsOperation(operation_->currentData().toInt()));
        }
    };
    connect(shape_, &QComboBox::currentIndexChanged, this, follow);
    connect(operation_, &QComboBox::currentIndexChanged, this, follow);
    return box;
}

QWidget* SegmentTools3d::makeViewBox() {
    auto* box = new QGroupBox(tr("The segment in the 3D view"), this);
    auto* layout = new QVBoxLayout(box);
    const auto add = [&](const QString& text, const QString& tip, auto slot) {
        auto* b = new QPushButton(text, box);
        b->setToolTip(tip);
        connect(b, &QPushButton::clicked, this, slot);
        layout->addWidget(b);
    };
    add(tr("Render the segment alone"), tr("The volume rendering masked by the segment"),
        [this] { showMasked(true); });
    add(tr("Render with the segment cut away"),
        tr("The volume rendering without the segment's voxels (the table, a bone)"),
        [this] { showMasked(false); });
    add(tr("Render the whole volume"), tr("The series' own voxels again"),
        [this] { showWholeVolume(); });
    add(tr("Show the segment's surface"), tr("Its surface in its colour in the 3D view"),
        [this] { showSurface(); });
    add(tr("Export the surface..."), tr("STL, PLY or OBJ, for printing"), [this] {
        const QString file = QFileDialog::getSaveFileName(
            this, tr("Export the segment's surface"), QString(), tr("Meshes (*.stl *.ply *.obj)"));
        if (!file.isEmpty()) {
            exportSurface(file);
        }
    });
    return box;
}

QWidget* SegmentTools3d::makeGrowBox() {
    auto* box = new QGroupBox(tr("Grow from seeds"), this);
    auto* form = new QFormLayout(box);
    growMargin_ = new QDoubleSpinBox(box);
    growMargin_->setRange(0.0, 500.0);
    growMargin_->setSuffix(tr(" mm"));
    growMargin_->setValue(grow_->marginMm());
    growMargin_->setToolTip(tr("The region grown: the seeds' box padded by this much "
                               "(0: the whole volume)"));
    growAfterStrokes_ = new QCheckBox(tr("Grow again after each stroke"), box);
    auto* run = new QPushButton(tr("Grow from seeds"), box);
    run->setToolTip(tr("The visible, unlocked segments holding voxels are the seeds; each "
                       "grows into its region (fast GrowCut)"));
    form->addRow(tr("Margin"), growMargin_);
    form->addRow(growAfterStrokes_);
    form->addRow(run);
    connect(growMargin_, &QDoubleSpinBox::valueChanged, grow_, &GrowFromSeedsEffect::setMarginMm);
    connect(growAfterStrokes_, &QCheckBox::toggled, grow_,
            &GrowFromSeedsEffect::setUpdateAfterStrokes);
    connect(run, &QPushButton::clicked, this, [this] { growFromSeeds(); });
    return box;
}

VolumeView* SegmentTools3d::viewOfActive(const QString& what, bool needVoxels) {
    SegmentationSession* session = panel_->session();
    const Segment* segment = session != nullptr ? session->active() : nullptr;
    QString why;
    VolumeView* view = nullptr;
    if (segment == nullptr) {
        why = tr("add or choose a segment first");
    } else if (needVoxels && (!segment->mask || !segment->mask->any())) {
        why = tr("%1 holds no voxel").arg(QString::fromStdString(segment->name));
    } else if ((view = viewFor_(*session->volume())) == nullptr) {
        why = tr("no 3D view shows this series: show it in 3D in a viewport first");
    }
    if (!why.isEmpty()) {
        emit message(tr("%1: %2").arg(what, why), 8000);
        return nullptr;
    }
    return view;
}

bool SegmentTools3d::setScissors(bool on) {
    if (scissors_) {
        scissors_->disconnect(); // its going now is no news for the button
        delete scissors_.data();
    }
    if (!on) {
        return true;
    }
    VolumeView* view = viewOfActive(tr("Scissors"), false);
    if (view == nullptr) {
        return false;
    }
    SegmentationSession* session = panel_->session();
    if (session->active()->locked) {
        emit message(tr("Scissors: the segment is locked"), 8000);
        return false;
    }
    scissors_ = new Scissors3d(view, &session->segmentation(), session->activeSegment());
    // The view going (its viewport turned to MPR) takes the scissors with it.
    connect(scissors_, &QObject::destroyed, scissorsOn_, [button = scissorsOn_] {
        const QSignalBlocker quiet(button);
        button->setChecked(false);
    });
    scissors_->setShape(Scissors3d::Shape(shape_->currentData().toInt()));
    scissors_->setOperation(ScissorsOperation(operation_->currentData().toInt()));
    scissorsSession_ = session;
    connect(scissors_.data(), &Scissors3d::cut, this, [this](std::size_t voxels) {
        if (scissorsSession_ && voxels > 0) {
            scissorsSession_->notifyChanged();
        }
        emit message(tr("Scissors: %n voxel(s) changed", nullptr, int(voxels)), 4000);
    });
    connect(scissors_.data(), &Scissors3d::refused, this,
            [this](const QString& why) { emit message(tr("Scissors: %1").arg(why), 8000); });
    // The segment cut follows the one chosen in the panel.
    connect(session, &SegmentationSession::activeSegmentChanged, scissors_.data(),
            &Scissors3d::setSegment);
    scissors_->setEnabled(true);
    return true;
}

bool SegmentTools3d::showMasked(bool segmentAlone) {
    VolumeView* view = viewOfActive(tr("Masked rendering"), true);
    if (view == nullptr) {
        return false;
    }
    if (maskedView_ != view) {
        masked_ = std::make_unique<MaskedRendering>(view);
        maskedView_ = view;
    }
    masked_->show(*panel_->session()->active()->mask,
                  segmentAlone ? MaskKeep::Inside : MaskKeep::Outside);
    return true;
}

bool SegmentTools3d::showWholeVolume() {
    if (masked_ && maskedView_) {
        masked_->clear();
    }
    masked_.reset();
    return true;
}

bool SegmentTools3d::showSurface() {
    VolumeView* view = viewOfActive(tr("Surface"), true);
    if (view == nullptr) {
        return false;
    }
    SegmentSurfaces3d surfaces(view, &panel_->session()->segmentation());
    const SurfaceResult& shown = surfaces.show(panel_->session()->activeSegment());
    emit message(tr("Surface of %1: %2 triangles")
                     .arg(QString::fromStdString(panel_->session()->active()->name))
                     .arg(shown.mesh.triangles.size()),
                 5000);
    return true;
}

bool SegmentTools3d::exportSurface(const QString& file) {
    SegmentationSession* session = panel_->session();
    const Segment* segment = session != nullptr ? session->active() : nullptr;
    if (segment == nullptr || !segment->mask || !segment->mask->any()) {
        emit message(tr("Export: choose a segment that holds voxels"), 8000);
        return false;
    }
    try {
        SegmentSurfaces3d surfaces(nullptr, &session->segmentation());
        surfaces.exportSurface(session->activeSegment(), file.toStdString());
    } catch (const std::exception& e) {
        emit message(tr("Export: %1").arg(QString::fromUtf8(e.what())), 0);
        return false;
    }
    emit message(tr("Surface of %1 written to %2").arg(QString::fromStdString(segment->name), file),
                 5000);
    return true;
}

bool SegmentTools3d::growFromSeeds() {
    SegmentationSession* session = panel_->session();
    if (session == nullptr) {
        emit message(tr("Grow from seeds: the active viewport shows no volume"), 8000);
        return false;
    }
    return grow_->grow(*session);
}

} // namespace lucent
