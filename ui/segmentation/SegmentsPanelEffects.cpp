// SegmentsPanel: the effects' tabs and what their buttons do.
#include <QButtonGroup>
#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QTabWidget>
#include <QTimer>
#include <QVBoxLayout>

#include "core/segmentation/SegmentEffects.h"
#include "core/segmentation/SegmentSmoothing.h"
#include "ui/segmentation/SegmentEditor.h"
#include "ui/segmentation/SegmentationSession.h"
#include "ui/segmentation/SegmentsPanel.h"
#include "ui/segmentation/ThresholdHistogram.h"

namespace lucent {
namespace {

QDoubleSpinBox* spin(QWidget* parent, double lo, double hi, double value, const QString& suffix,
                     int decimals = 1) {
    auto* box = new QDoubleSpinBox(parent);
    box->setRange(lo, hi);
    box->setDecimals(decimals);
    box->setValue(value);
    box->setSuffix(suffix);
    return box;
}

QPushButton* button(QWidget* parent, const QString& text, const std::function<void()>& f) {
    auto* b = new QPushButton(text, parent);
    QObject::connect(b, &QPushButton::clicked, parent, f);
    return b;
}

} // namespace

QWidget* SegmentsPanel::makeEffects() {
    auto* tabs = new QTabWidget(this);
    tabs->addTab(makePaintTab(), tr("Paint"));
    tabs->addTab(makeThresholdTab(), tr("Threshold"));
    tabs->addTab(makeIslandsTab(), tr("Islands"));
    tabs->addTab(makeMarginTab(), tr("Margin, smooth"));
    tabs->addTab(makeLogicalTab(), tr("Logical"));
    auto* more = new QWidget(tabs);
    more_ = new QVBoxLayout(more);
    more_->addStretch(1);
    tabs->addTab(more, tr("More"));
    // Leaving the threshold tab ends its preview.
    connect(tabs, &QTabWidget::currentChanged, this, [this, tabs](int index) {
        if (tabs->tabText(index) != tr("Threshold")) {
            setThresholdPreview(false);
        }
    });
    return tabs;
}

QWidget* SegmentsPanel::makePaintTab() {
    auto* tab = new QWidget(this);
    auto* form = new QFormLayout(tab);
    auto* row = new QHBoxLayout;
    tools_ = new QButtonGroup(tab);
    const std::pair<SegmentTool, QString> kTools[] = {
        {SegmentTool::None, tr("Navigate")},
        {SegmentTool::Paint, tr("Paint")},
        {SegmentTool::Erase, tr("Erase")},
        {SegmentTool::Draw, tr("Draw")},
    };
    for (const auto& [tool, text] : kTools) {
        auto* b = new QPushButton(text, tab);
        b->setCheckable(true);
        b->setChecked(tool == editor_->tool());
        tools_->addButton(b, static_cast<int>(tool));
        row->addWidget(b);
    }
    tools_->button(static_cast<int>(SegmentTool::Draw))
        ->setToolTip(tr("Drag a closed outline, or click its corners and double-click (Enter) "
                        "to fill it on the slice"));
    connect(tools_, &QButtonGroup::idClicked, this,
            [this](int id) { editor_->setTool(static_cast<SegmentTool>(id)); });
    connect(editor_, &SegmentEditor::toolChanged, this, [this](SegmentTool tool) {
        if (QAbstractButton* b = tools_->button(static_cast<int>(tool))) {
            b->setChecked(true);
        } else if (tools_->checkedButton() != nullptr) {
            tools_->setExclusive(false);
            tools_->checkedButton()->setChecked(false);
            tools_->setExclusive(true);
        }
    });
    form->addRow(row);
    brushRadius_ = spin(tab, 0.5, 100.0, editor_->brushRadiusMm(), tr(" mm"));
    connect(brushRadius_, &QDoubleSpinBox::valueChanged, editor_, &SegmentEditor::setBrushRadiusMm);
    form->addRow(tr("Brush radius"), brushRadius_);
    sphere_ = new QCheckBox(tr("Sphere (else this slice only)"), tab);
    sphere_->setChecked(editor_->brushSphere());
    connect(sphere_, &QCheckBox::toggled, editor_, &SegmentEditor::setBrushSphere);
    form->addRow(sphere_);
    return tab;
}

QWidget* SegmentsPanel::makeThresholdTab() {
    auto* tab = new QWidget(this);
    auto* form = new QFormLayout(tab);
    histogram_ = new ThresholdHistogram(tab);
    form->addRow(histogram_);
    lower_ = spin(tab, -100000.0, 100000.0, 200.0, QString(), 0);
    upper_ = spin(tab, -100000.0, 100000.0, 3000.0, QString(), 0);
    histogram_->setRange(lower_->value(), upper_->value());
    auto* range = new QHBoxLayout;
    range->addWidget(lower_);
    range->addWidget(new QLabel(tr("to"), tab));
    range->addWidget(upper_);
    form->addRow(tr("Range"), range);
    const auto edited = [this] {
        histogram_->setRange(lower_->value(), upper_->value());
        if (preview_->isChecked()) {
            previewTimer_->start();
        }
    };
    connect(lower_, &QDoubleSpinBox::valueChanged, this, edited);
    connect(upper_, &QDoubleSpinBox::valueChanged, this, edited);
    connect(histogram_, &ThresholdHistogram::rangeChosen, this,
            [this](double lo, double hi) { setThresholdRange(lo, hi); });
    preview_ = new QCheckBox(tr("Preview in the views"), tab);
    connect(preview_, &QCheckBox::toggled, this, [this](bool on) {
        if (!updating_) {
            setThresholdPreview(on);
        }
    });
    auto* apply = button(tab, tr("Apply"), [this] { applyThreshold(); });
    auto* row = new QHBoxLayout;
    row->addWidget(preview_);
    row->addWidget(apply);
    form->addRow(row);
    return tab;
}

QWidget* SegmentsPanel::makeIslandsTab() {
    auto* tab = new QWidget(this);
    auto* form = new QFormLayout(tab);
    form->addRow(button(tab, tr("Keep the largest island"), [this] { keepLargestIsland(); }));
    auto* minimum = spin(tab, 0.0, 1e7, 1000.0, tr(" mm³"), 0);
    auto* row = new QHBoxLayout;
    row->addWidget(minimum);
    row->addWidget(button(tab, tr("Remove smaller islands"),
                          [this, minimum] { removeSmallIslands(minimum->value()); }));
    form->addRow(tr("Under"), row);
    auto* pick = button(tab, tr("Keep the island clicked in a view"),
                        [this] { editor_->setTool(SegmentTool::PickIsland); });
    form->addRow(pick);
    return tab;
}

QWidget* SegmentsPanel::makeMarginTab() {
    auto* tab = new QWidget(this);
    auto* form = new QFormLayout(tab);
    auto* mm = spin(tab, 0.1, 200.0, 3.0, tr(" mm"));
    auto* row = new QHBoxLayout;
    row->addWidget(mm);
    row->addWidget(button(tab, tr("Grow"), [this, mm] { margin(mm->value()); }));
    row->addWidget(button(tab, tr("Shrink"), [this, mm] { margin(-mm->value()); }));
    form->addRow(tr("Margin"), row);
    auto* shell = spin(tab, 0.1, 100.0, 2.0, tr(" mm"));
    auto* hollowRow = new QHBoxLayout;
    hollowRow->addWidget(shell);
    hollowRow->addWidget(button(tab, tr("Hollow"), [this, shell] { hollow(shell->value()); }));
    form->addRow(tr("Shell"), hollowRow);
    auto* kernel = spin(tab, 0.1, 100.0, 3.0, tr(" mm"));
    auto* medianRow = new QHBoxLayout;
    medianRow->addWidget(kernel);
    medianRow->addWidget(button(tab, tr("Median"), [this, kernel] { median(kernel->value()); }));
    form->addRow(tr("Smooth"), medianRow);
    auto* radius = spin(tab, 0.1, 100.0, 2.0, tr(" mm"));
    auto* closingRow = new QHBoxLayout;
    closingRow->addWidget(radius);
    closingRow->addWidget(button(tab, tr("Closing"), [this, radius] { closing(radius->value()); }));
    form->addRow(tr("Fill gaps"), closingRow);
    return tab;
}

QWidget* SegmentsPanel::makeLogicalTab() {
    auto* tab = new QWidget(this);
    auto* form = new QFormLayout(tab);
    other_ = new QComboBox(tab);
    form->addRow(tr("With"), other_);
    const auto with = [this] { return other_->currentData().value<std::uint32_t>(); };
    auto* row = new QHBoxLayout;
    row->addWidget(button(tab, tr("Add"), [this, with] { combine(Logical::Add, with()); }));
    row->addWidget(
        button(tab, tr("Subtract"), [this, with] { combine(Logical::Subtract, with()); }));
    row->addWidget(
        button(tab, tr("Intersect"), [this, with] { combine(Logical::Intersect, with()); }));
    form->addRow(row);
    form->addRow(button(tab, tr("Invert"), [this] { invert(); }));
    return tab;
}

QPushButton* SegmentsPanel::addEffectButton(const QString& text, const QString& toolTip,
                                            SegmentAction action) {
    auto* b = new QPushButton(text, this);
    b->setToolTip(toolTip);
    connect(b, &QPushButton::clicked, this, [this, text, action = std::move(action)] {
        if (!session_ || session_->active() == nullptr) {
            say(tr("%1: add or choose a segment first").arg(text));
        } else if (session_->active()->locked) {
            say(tr("%1: the segment is locked").arg(text));
        } else {
            action(*session_, session_->activeSegment());
        }
    });
    more_->insertWidget(more_->count() - 1, b);
    return b;
}

void SegmentsPanel::addEffectWidget(QWidget* widget) {
    more_->insertWidget(more_->count() - 1, widget);
}

void SegmentsPanel::setThresholdRange(double lo, double hi) {
    lower_->setValue(std::min(lo, hi));
    upper_->setValue(std::max(lo, hi));
}

void SegmentsPanel::setThresholdPreview(bool on) {
    if (preview_->isChecked() != on) {
        preview_->setChecked(on); // comes back here through toggled
        return;
    }
    if (on) {
        updateThresholdPreview();
    } else if (session_) {
        previewTimer_->stop();
        session_->setPreview(std::nullopt);
    }
}

void SegmentsPanel::updateThresholdPreview() {
    if (!session_ || !preview_->isChecked()) {
        return;
    }
    if (session_->active() == nullptr) {
        session_->setPreview(std::nullopt);
        say(tr("Threshold: add or choose a segment first"));
        return;
    }
    session_->setPreview(SegmentationSession::Preview{
        session_->activeSegment(), std::make_shared<const SegmentMask>(thresholdMask(
                                       *session_->volume(), lower_->value(), upper_->value()))});
}

bool SegmentsPanel::applyThreshold() {
    const double lo = lower_->value(), hi = upper_->value();
    const bool done = editor_->applyToActive(
        tr("Threshold %1 to %2").arg(lo).arg(hi),
        [lo, hi](const SegmentMask&, const SegmentationSession& s) {
            return thresholdMask(*s.volume(), lo, hi);
        },
        "Lucent threshold");
    setThresholdPreview(false);
    return done;
}

bool SegmentsPanel::keepLargestIsland() {
    return editor_->applyToActive(tr("Keep the largest island"),
                                  [](const SegmentMask& m, const SegmentationSession&) {
                                      return lucent::keepLargestIsland(m);
                                  });
}

bool SegmentsPanel::removeSmallIslands(double minMm3) {
    return editor_->applyToActive(tr("Remove islands under %1 mm³").arg(minMm3),
                                  [minMm3](const SegmentMask& m, const SegmentationSession& s) {
                                      return lucent::removeSmallIslands(
                                          m, s.segmentation().geometry(), minMm3);
                                  });
}

bool SegmentsPanel::margin(double mm) {
    return editor_->applyToActive(mm > 0 ? tr("Grow by %1 mm").arg(mm)
                                         : tr("Shrink by %1 mm").arg(-mm),
                                  [mm](const SegmentMask& m, const SegmentationSession& s) {
                                      return marginMask(m, s.segmentation().geometry(), mm);
                                  });
}

bool SegmentsPanel::hollow(double thicknessMm) {
    return editor_->applyToActive(
        tr("Hollow, %1 mm shell").arg(thicknessMm),
        [thicknessMm](const SegmentMask& m, const SegmentationSession& s) {
            return hollowMask(m, s.segmentation().geometry(), thicknessMm);
        });
}

bool SegmentsPanel::median(double kernelMm) {
    return editor_->applyToActive(tr("Median %1 mm").arg(kernelMm),
                                  [kernelMm](const SegmentMask& m, const SegmentationSession& s) {
                                      return medianMask(m, s.segmentation().geometry(), kernelMm);
                                  });
}

bool SegmentsPanel::closing(double radiusMm) {
    return editor_->applyToActive(tr("Closing %1 mm").arg(radiusMm),
                                  [radiusMm](const SegmentMask& m, const SegmentationSession& s) {
                                      return closingMask(m, s.segmentation().geometry(), radiusMm);
                                  });
}

bool SegmentsPanel::combine(Logical operation, std::uint32_t other) {
    const Segment* with = session_ ? session_->segmentation().find(other) : nullptr;
    if (with == nullptr || other == session_->activeSegment()) {
        say(tr("Choose another segment to combine with"));
        return false;
    }
    const std::shared_ptr<const SegmentMask> mask = with->mask;
    const QString name = QString::fromStdString(with->name);
    const QString what = operation == Logical::Add        ? tr("Add %1").arg(name)
                         : operation == Logical::Subtract ? tr("Subtract %1").arg(name)
                                                          : tr("Intersect with %1").arg(name);
    return editor_->applyToActive(
        what, [operation, mask](const SegmentMask& m, const SegmentationSession&) {
            SegmentMask out = m;
            if (operation == Logical::Add) {
                out |= *mask;
            } else if (operation == Logical::Subtract) {
                out.subtract(*mask);
            } else {
                out &= *mask;
            }
            return out;
        });
}

bool SegmentsPanel::invert() {
    return editor_->applyToActive(tr("Invert"),
                                  [](const SegmentMask& m, const SegmentationSession&) {
                                      SegmentMask out = m;
                                      return out.invert();
                                  });
}

} // namespace lucent
