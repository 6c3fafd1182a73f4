#include "ui/viewports/GridShape.h"

#include <algorithm>

namespace lucent {

GridShape regularGridShape(int rows, int columns) {
    rows = std::clamp(rows, 1, 4);
    columns = std::clamp(columns, 1, 4);
    GridShape shape{QStringLiteral("%1x%2").arg(rows).arg(columns), rows, columns, {}};
    for (int r = 0; r < rows; ++r) {
        for (int c = 0; c < columns; ++c) {
            shape.cells.push_back({r, c, 1, 1});
        }
    }
    return shape;
}

std::vector<GridShape> standardGridShapes() {
    std::vector<GridShape> shapes;
    for (const auto& [r, c] :
         {std::pair{1, 1}, {1, 2}, {2, 1}, {2, 2}, {1, 3}, {2, 3}, {3, 3}, {3, 4}, {4, 4}}) {
        shapes.push_back(regularGridShape(r, c));
    }
    shapes.push_back({QStringLiteral("1+2"), 2, 2, {{0, 0, 2, 1}, {0, 1, 1, 1}, {1, 1, 1, 1}}});
    shapes.push_back({QStringLiteral("2+1"), 2, 2, {{0, 0, 1, 1}, {1, 0, 1, 1}, {0, 1, 2, 1}}});
    return shapes;
}

std::optional<GridShape> gridShape(const QString& name) {
    for (GridShape& shape : standardGridShapes()) {
        if (shape.name == name) {
            return std::move(shape);
        }
    }
    return std::nullopt;
}

} // namespace lucent
