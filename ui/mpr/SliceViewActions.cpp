// SliceView's keys, context menu, window presets, slab controls, cine and measurements.
#include <algorithm>
#include <array>

#include <QActionGroup>
#include <QKeyEvent>
#include <QMenu>
#include <QTimer>

#include "core/mpr/WindowPresets.h"
#include "ui/mpr/MprCursor.h"
#include "ui/mpr/SliceView.h"

namespace lucent {

namespace {

constexpr std::array<double, 9> kSlabThicknesses{1.0, 2.0, 3.0, 5.0, 10.0, 15.0, 20.0, 30.0, 50.0};

const char* slabModeName(SlabMode mode) {
    switch (mode) {
    case SlabMode::Mip:
        return "MIP";
    case SlabMode::MinIp:
        return "MinIP";
    case SlabMode::Average:
        return "Average";
    }
    return "?";
}

} // namespace

void SliceView::applyWindowPreset(int index) {
    const auto presets = windowPresets();
    if (index < 0 || index >= static_cast<int>(presets.size())) {
        return;
    }
    const WindowPreset& preset = presets[static_cast<std::size_t>(index)];
    cursor_->setWindow(preset.center, preset.width);
}

void SliceView::setMeasurements(SeriesMeasurements* measurements) {
    if (SeriesMeasurements* before = measure_.document()) {
        disconnect(before, nullptr, this, nullptr);
    }
    measure_.setDocument(measurements);
    if (measurements != nullptr) {
        connect(measurements, &SeriesMeasurements::changed, this, qOverload<>(&QWidget::update));
        connect(measurements, &SeriesMeasurements::selectionChanged, this,
                qOverload<>(&QWidget::update));
    }
    update();
}

void SliceView::deleteSelectedMeasurement() {
    if (SeriesMeasurements* m = measure_.document(); m != nullptr && m->selected() != 0) {
        m->remove(m->selected());
    }
}

void SliceView::clearMeasurements() {
    if (SeriesMeasurements* m = measure_.document()) {
        m->clear();
    }
}

void SliceView::cycleSlabMode() {
    // Thin -> MIP -> MinIP -> average -> thin.
    if (slabThickness_ <= 0.0) {
        setSlab(lastSlabThickness_, SlabMode::Mip);
    } else if (slabMode_ == SlabMode::Mip) {
        setSlab(slabThickness_, SlabMode::MinIp);
    } else if (slabMode_ == SlabMode::MinIp) {
        setSlab(slabThickness_, SlabMode::Average);
    } else {
        setSlab(0.0, slabMode_);
    }
}

void SliceView::changeSlabThickness(int steps) {
    const double now = slabThickness_ > 0.0 ? slabThickness_ : lastSlabThickness_;
    auto at = std::lower_bound(kSlabThicknesses.begin(), kSlabThicknesses.end(), now - 1e-9);
    int index = static_cast<int>(at - kSlabThicknesses.begin());
    if (steps < 0 && (at == kSlabThicknesses.end() || *at > now + 1e-9)) {
        ++index; // between two sizes: one step down is the smaller one
    }
    index = std::clamp(index + steps, 0, static_cast<int>(kSlabThicknesses.size()) - 1);
    setSlab(kSlabThicknesses[static_cast<std::size_t>(index)], slabMode_);
}

bool SliceView::cineRunning() const {
    return cine_->isActive();
}

int SliceView::cineIntervalMs() const {
    return cine_->interval();
}

void SliceView::setCineRunning(bool running) {
    if (running && volume_ && !volume_->empty()) {
        cine_->start();
    } else {
        cine_->stop();
    }
    update();
}

void SliceView::nextCineFrame() {
    // Forward through the slices; after the last one, back to the first.
    if (!moveSlices(1.0)) {
        moveSlices(-1e9);
    }
}

void SliceView::keyPressEvent(QKeyEvent* event) {
    const int key = event->key();
    if (key >= Qt::Key_1 && key <= Qt::Key_8) {
        applyWindowPreset(key - Qt::Key_1);
    } else if (key == Qt::Key_S) {
        cycleSlabMode();
    } else if (key == Qt::Key_BracketRight) {
        changeSlabThickness(1);
    } else if (key == Qt::Key_BracketLeft) {
        changeSlabThickness(-1);
    } else if (const std::optional<Tool> tool = sliceToolForKey(*event)) {
        // Esc while drawing drops the drawing and keeps the tool.
        if (*tool == Tool::Crosshair && measure_.busy()) {
            measure_.cancel();
            update();
        } else {
            setTool(*tool);
        }
    } else if ((key == Qt::Key_Return || key == Qt::Key_Enter) && tool_ == Tool::CurvedPath) {
        finishPath();
    } else if (key == Qt::Key_Delete || key == Qt::Key_Backspace) {
        deleteSelectedMeasurement();
    } else if (key == Qt::Key_C) {
        setCineRunning(!cineRunning());
    } else if (key == Qt::Key_R) {
        resetZoomAndPan();
    } else if (key == Qt::Key_O) {
        cursor_->resetRotations();
    } else if (key == Qt::Key_Menu) {
        showContextMenu(mapToGlobal(rect().center()));
    } else {
        QWidget::keyPressEvent(event);
        return;
    }
    event->accept();
}

void SliceView::fillContextMenu(QMenu& menu) {
    QMenu* window = menu.addMenu(QStringLiteral("Window preset"));
    const auto presets = windowPresets();
    for (std::size_t n = 0; n < presets.size(); ++n) {
        const WindowPreset& p = presets[n];
        QAction* action = window->addAction(
            QStringLiteral("%1 (W %2 L %3)\t%4")
                .arg(QString::fromUtf8(p.name.data(), static_cast<int>(p.name.size())))
                .arg(p.width)
                .arg(p.center)
                .arg(n + 1));
        const int index = static_cast<int>(n);
        connect(action, &QAction::triggered, this, [this, index] { applyWindowPreset(index); });
    }
    window->addSeparator();
    QAction* inverted = window->addAction(QStringLiteral("Inverted grey"));
    inverted->setCheckable(true);
    inverted->setChecked(cursor_->invertedGrey());
    connect(inverted, &QAction::toggled, cursor_, &MprCursor::setInvertedGrey);

    QMenu* slab = menu.addMenu(QStringLiteral("Slab"));
    auto* modes = new QActionGroup(slab);
    QAction* thin = slab->addAction(QStringLiteral("Thin slice"));
    thin->setCheckable(true);
    thin->setChecked(slabThickness_ <= 0.0);
    modes->addAction(thin);
    connect(thin, &QAction::triggered, this, [this] { setSlab(0.0, slabMode_); });
    for (const SlabMode mode : {SlabMode::Mip, SlabMode::MinIp, SlabMode::Average}) {
        QAction* a = slab->addAction(QString::fromLatin1(slabModeName(mode)));
        a->setCheckable(true);
        a->setChecked(slabThickness_ > 0.0 && slabMode_ == mode);
        modes->addAction(a);
        connect(a, &QAction::triggered, this, [this, mode] {
            setSlab(slabThickness_ > 0.0 ? slabThickness_ : lastSlabThickness_, mode);
        });
    }
    slab->addSeparator();
    for (const double mm : kSlabThicknesses) {
        QAction* a = slab->addAction(QStringLiteral("%1 mm").arg(mm));
        a->setCheckable(true);
        a->setChecked(slabThickness_ == mm);
        connect(a, &QAction::triggered, this, [this, mm] { setSlab(mm, slabMode_); });
    }

    menu.addSeparator();
    for (const SliceToolInfo& info : sliceTools()) {
        QAction* a = menu.addAction(QStringLiteral("%1\t%2").arg(QString::fromLatin1(info.name),
                                                                 QString::fromLatin1(info.key)));
        a->setCheckable(true);
        a->setChecked(tool_ == info.tool);
        a->setStatusTip(QString::fromLatin1(info.help));
        const Tool t = info.tool;
        connect(a, &QAction::triggered, this, [this, t] { setTool(t); });
    }
    const SeriesMeasurements* measurements = measure_.document();
    QAction* remove = menu.addAction(QStringLiteral("Delete measurement\tDel"));
    remove->setEnabled(measurements != nullptr && measurements->selected() != 0);
    connect(remove, &QAction::triggered, this, &SliceView::deleteSelectedMeasurement);
    QAction* clear = menu.addAction(QStringLiteral("Clear measurements"));
    clear->setEnabled(measurements != nullptr && !measurements->measurements().empty());
    connect(clear, &QAction::triggered, this, &SliceView::clearMeasurements);
    menu.addSeparator();
    QAction* cine = menu.addAction(QStringLiteral("Cine\tC"));
    cine->setCheckable(true);
    cine->setChecked(cineRunning());
    connect(cine, &QAction::toggled, this, &SliceView::setCineRunning);
    connect(menu.addAction(QStringLiteral("Reset zoom and pan\tR")), &QAction::triggered, this,
            &SliceView::resetZoomAndPan);
    connect(menu.addAction(QStringLiteral("Reset oblique planes\tO")), &QAction::triggered, cursor_,
            &MprCursor::resetRotations);
}

void SliceView::showContextMenu(const QPoint& globalPos) {
    auto* menu = new QMenu(this);
    menu->setAttribute(Qt::WA_DeleteOnClose);
    fillContextMenu(*menu);
    menu->popup(globalPos);
}

} // namespace lucent
