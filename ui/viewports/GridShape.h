#pragma once

#include <optional>
#include <vector>

#include <QString>

namespace lucent {

// Where a viewport sits in the grid: its top-left cell and how many rows and columns
// it spans.
struct GridCell {
    int row = 0;
    int column = 0;
    int rowSpan = 1;
    int columnSpan = 1;
};

// An arrangement of viewports: "RxC" (1x1 up to 4x4) or an asymmetric one:
// "1+2" (one tall viewport on the left, two stacked on the right) and "2+1" (two
// stacked on the left, one tall on the right).
struct GridShape {
    QString name;
    int rows = 1;
    int columns = 1;
    std::vector<GridCell> cells;
};

// Every shape the View menu offers, 1x1 first.
std::vector<GridShape> standardGridShapes();
// A shape of standardGridShapes() by name, or nothing.
std::optional<GridShape> gridShape(const QString& name);
// A shape of any rows x columns (1..4 each), one viewport per cell.
GridShape regularGridShape(int rows, int columns);

} // namespace lucent
