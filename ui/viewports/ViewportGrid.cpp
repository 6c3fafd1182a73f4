#include "ui/viewports/ViewportGrid.h"

#include <QGridLayout>

#include "ui/viewports/Viewport.h"

namespace lucent {

ViewportGrid::ViewportGrid(QWidget* parent) : QWidget(parent), grid_(new QGridLayout(this)) {
    grid_->setContentsMargins(0, 0, 0, 0);
    grid_->setSpacing(2);
    setShape(regularGridShape(1, 2));
}

Viewport* ViewportGrid::viewport(int index) const {
    return index >= 0 && index < count() ? viewports_[static_cast<std::size_t>(index)] : nullptr;
}

Viewport* ViewportGrid::makeViewport(int number) {
    auto* viewport = new Viewport(number, this);
    connect(viewport, &Viewport::pressed, this, [this, viewport] { setActiveViewport(viewport); });
    connect(viewport, &Viewport::contentChanged, this,
            [this, viewport] { emit viewportContentChanged(viewport); });
    connect(viewport, &Viewport::seriesDropped, this,
            [this, viewport](const QString& path, const QString& series) {
                setActiveViewport(viewport);
                emit seriesDropped(viewport, path, series);
            });
    return viewport;
}

void ViewportGrid::setShape(const GridShape& shape) {
    shape_ = shape;
    const std::size_t wanted = shape.cells.size();
    while (viewports_.size() > wanted) {
        Viewport* gone = viewports_.back();
        viewports_.pop_back();
        grid_->removeWidget(gone);
        if (gone == active_) {
            active_ = nullptr;
        }
        delete gone;
    }
    while (viewports_.size() < wanted) {
        viewports_.push_back(makeViewport(static_cast<int>(viewports_.size()) + 1));
    }
    for (int r = 0; r < grid_->rowCount(); ++r) {
        grid_->setRowStretch(r, 0);
    }
    for (int c = 0; c < grid_->columnCount(); ++c) {
        grid_->setColumnStretch(c, 0);
    }
    for (std::size_t n = 0; n < wanted; ++n) {
        const GridCell& cell = shape.cells[n];
        grid_->removeWidget(viewports_[n]);
        grid_->addWidget(viewports_[n], cell.row, cell.column, cell.rowSpan, cell.columnSpan);
    }
    for (int r = 0; r < shape.rows; ++r) {
        grid_->setRowStretch(r, 1);
    }
    for (int c = 0; c < shape.columns; ++c) {
        grid_->setColumnStretch(c, 1);
    }
    if (active_ == nullptr && !viewports_.empty()) {
        setActiveViewport(viewports_.front());
    }
    emit viewportsChanged();
}

void ViewportGrid::setActiveViewport(Viewport* viewport) {
    if (viewport == active_) {
        return;
    }
    if (active_ != nullptr) {
        active_->setActive(false);
    }
    active_ = viewport;
    if (active_ != nullptr) {
        active_->setActive(true);
    }
    emit activeViewportChanged(active_);
}

} // namespace lucent
