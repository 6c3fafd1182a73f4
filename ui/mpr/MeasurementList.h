#pragma once

#include <cstdint>

#include <QPointer>
#include <QWidget>

#include "ui/mpr/SeriesMeasurements.h"

class QLabel;
class QPushButton;
class QTableWidget;

namespace lucent {

class MprCursor;

// The measurement list (a dock of the main window): one row per measurement of the
// series, kind, name, value, plane (Axial/Coronal/Sagittal/Oblique) and slice. A click
// on a row selects the measurement and moves the views to it (showMeasurement);
// the name cell is edited in place (a rename), and an arrow's value cell (its text); Del or the
// Delete button removes the selected one. Read-only measurements (a foreign SR's) are grey and
// cannot be renamed or deleted.
class MeasurementList : public QWidget {
    Q_OBJECT

public:
    enum Column { Kind, Name, Value, Plane, Slice, ColumnCount };

    explicit MeasurementList(MprCursor* cursor, QWidget* parent = nullptr);

    void setMeasurements(SeriesMeasurements* measurements);
    QTableWidget* table() const { return table_; }
    QPushButton* deleteButton() const { return delete_; }
    // Lists what other reports hold that cannot be shown; hidden when there is none.
    QLabel* notShownLabel() const { return notShown_; }
    // The measurement of a row; 0 for none.
    std::uint64_t idAt(int row) const;

private:
    void refresh();
    void showSelection();
    void rowClicked(int row);
    void cellEdited(int row, int column);
    void deleteSelected();

    MprCursor* cursor_;
    QPointer<SeriesMeasurements> measurements_;
    QTableWidget* table_;
    QPushButton* delete_;
    QPushButton* clear_;
    QLabel* notShown_;
    bool refreshing_ = false;
};

} // namespace lucent
