#pragma once

#include <memory>
#include <string>
#include <vector>

#include <QMetaType>
#include <QString>
#include <QWidget>

#include "core/followup/Recist.h"
#include "ui/mpr/LesionMarks.h"

class QLabel;
class QPushButton;
class QTableWidget;

namespace lucent {

class MeasurementArchive;
class StudyStore;

// The RECIST 1.1 follow-up of one patient (a dock of the main window): every tracked lesion
// by timepoint (its diameter in mm; "present" for a non-target lesion), the sum of
// diameters, its change from baseline and from the nadir, the response and why
// (core/followup/Recist.h for the rules), read from the SRs of the local study store
// (core/followup/FollowUpCollection.h). "Export CSV..." writes the same table as CSV.
// A click on a lesion's row says where it was measured, per timepoint, so that the views
// can go to it in every study. refresh() reads the store again: call it when measurements
// were saved (MeasurementAutosave::saved).
class FollowUpPanel : public QWidget {
    Q_OBJECT

public:
    explicit FollowUpPanel(QWidget* parent = nullptr);
    ~FollowUpPanel() override;

    void setStoreFolder(const QString& folder); // and refresh()
    void showPatient(const QString& patientId); // and refresh(); "" shows nothing
    const QString& patientId() const { return patientId_; }
    void refresh();

    const FollowUpTable& table() const { return table_; }
    // The patient's lesions first measured before the study of `seriesUid` (all of them when
    // its date is unknown): MeasurementList::setLesionChoices takes this.
    std::vector<LesionChoice> earlierLesions(const std::string& seriesUid) const;
    // Writes the table as CSV; false with the reason in `error` when it cannot.
    bool exportCsv(const QString& file, QString* error = nullptr) const;

    QTableWidget* grid() const { return grid_; }
    QPushButton* exportButton() const { return export_; }
    QLabel* statusLabel() const { return status_; }

signals:
    // A lesion's row was clicked: its tracking UID and, per timepoint where it was
    // measured (oldest first), the series and the lesion's centre in patient mm (LPS).
    void lesionActivated(const QString& trackingUid,
                         const std::vector<lucent::LesionLocation>& where);

private:
    void showTable();
    void cellClicked(int row);
    void exportClicked();

    // Opened once per folder: the archive keeps the image headers it read.
    std::unique_ptr<StudyStore> store_;
    std::unique_ptr<MeasurementArchive> archive_;
    QString folder_;
    QString patientId_;
    FollowUpTable table_;
    QTableWidget* grid_;
    QPushButton* export_;
    QLabel* status_;
};

} // namespace lucent

Q_DECLARE_METATYPE(std::vector<lucent::LesionLocation>)
