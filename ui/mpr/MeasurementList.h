#pragma once

#include <cstdint>

#include <QPointer>
#include <QWidget>

#include "ui/mpr/LesionMarks.h"
#include "ui/mpr/SeriesMeasurements.h"

class QLabel;
class QMenu;
class QPushButton;
class QTableWidget;

namespace lucent {

class MprCursor;

// The measurement list (a dock of the main window): one row per measurement of the
// series, kind, name, value, plane (Axial/Coronal/Sagittal/Oblique) and slice. A click
// on a row selects the measurement and moves the views to it (showMeasurement);
// the name cell is edited in place (a rename), and an arrow's value cell (its text); Del or the
// Delete button removes the selected one. Read-only measurements (a foreign SR's) are grey and
// cannot be renamed or deleted. The context menu of a row marks its measurement as a RECIST
// target or non-target lesion, a lymph node, or the same lesion as one of the patient's
// earlier timepoints (ui/mpr/LesionMarks.h); the Lesion column shows the mark.
class MeasurementList : public QWidget {
    Q_OBJECT

public:
    enum Column { Kind, Name, Value, Plane, Slice, Lesion, ColumnCount };

    explicit MeasurementList(MprCursor* cursor, QWidget* parent = nullptr);

    void setMeasurements(SeriesMeasurements* measurements);
    QTableWidget* table() const { return table_; }
    QPushButton* deleteButton() const { return delete_; }
    // Lists what other reports hold that cannot be shown; hidden when there is none.
    QLabel* notShownLabel() const { return notShown_; }
    // The measurement of a row; 0 for none.
    std::uint64_t idAt(int row) const;
    // Where "Same lesion as" takes the patient's earlier lesions from (none: an empty menu).
    void setLesionChoices(LesionChoices choices) { choices_ = std::move(choices); }
    // The context menu of a measurement (the lesion marks); the caller owns it.
    QMenu* contextMenu(std::uint64_t id);

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
    LesionChoices choices_;
};

} // namespace lucent
