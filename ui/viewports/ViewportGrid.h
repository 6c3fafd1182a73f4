#pragma once

#include <vector>

#include <QWidget>

#include "ui/viewports/GridShape.h"

class QGridLayout;

namespace lucent {

class Viewport;

// The viewports of the reading area in a GridShape. Changing the shape keeps the
// viewports that still have a cell (with their series), adds empty ones and deletes
// the rest. The viewport last pressed is the active one.
class ViewportGrid : public QWidget {
    Q_OBJECT

public:
    explicit ViewportGrid(QWidget* parent = nullptr);

    void setShape(const GridShape& shape);
    const GridShape& shape() const { return shape_; }

    int count() const { return static_cast<int>(viewports_.size()); }
    Viewport* viewport(int index) const;
    const std::vector<Viewport*>& viewports() const { return viewports_; }
    Viewport* activeViewport() const { return active_; }
    void setActiveViewport(Viewport* viewport);

signals:
    void activeViewportChanged(lucent::Viewport* viewport);
    // Viewports were added or removed (a new shape).
    void viewportsChanged();
    void seriesDropped(lucent::Viewport* viewport, const QString& path, const QString& series);
    // A viewport shows something new (a series, another view, or nothing).
    void viewportContentChanged(lucent::Viewport* viewport);

private:
    Viewport* makeViewport(int number);

    GridShape shape_;
    QGridLayout* grid_;
    std::vector<Viewport*> viewports_;
    Viewport* active_ = nullptr;
};

} // namespace lucent
