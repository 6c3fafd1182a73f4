#pragma once
// The PACS query panel: node, filters (patient name with * and ?, patient ID,
// accession, modalities, study date range with presets), results as a
// study -> series tree, and Retrieve for the selected series.

#include <vector>

#include <QDate>
#include <QWidget>

#include "core/pacs/PacsConfig.h"
#include "core/pacs/PacsService.h"

class QComboBox;
class QDateEdit;
class QLabel;
class QLineEdit;
class QPushButton;
class QTreeWidget;

namespace lucent {

class PacsQueryPanel : public QWidget {
    Q_OBJECT

public:
    enum class DatePreset { AnyDate, Today, Last7Days, LastMonth, Custom };
    enum Column { Name, Id, Date, Modality, Description, Instances };
    static constexpr int kUidRole = Qt::UserRole;          // study or series UID
    static constexpr int kStudyUidRole = Qt::UserRole + 1; // on series items

    explicit PacsQueryPanel(PacsService* service, QWidget* parent = nullptr);

    void setNodes(const QList<PacsNodeConfig>& nodes);
    // The selected node; nullptr when there is none.
    const PacsNodeConfig* currentNode() const;

    // Sets the date range: today; the last 7 days (today and the 6 before);
    // the last month (the same day a month ago up to today); any date.
    void applyPreset(DatePreset preset);
    // The filters as entered. On bad input, error names the field and the
    // filter must not be used.
    QueryFilter filter(QString* error) const;

    void search();
    // Queues the selected series (a selected study means all its series).
    void retrieveSelected();

    QTreeWidget* results() const { return results_; }
    QLabel* status() const { return status_; }

private:
    void showResults(const std::vector<PacsStudyResult>& results);
    void showError(const QString& message);

    PacsService* service_;
    QList<PacsNodeConfig> nodes_;
    QComboBox* node_;
    QLineEdit* patientName_;
    QLineEdit* patientId_;
    QLineEdit* accession_;
    QLineEdit* modalities_;
    QComboBox* preset_;
    QDateEdit* from_;
    QDateEdit* to_;
    QPushButton* search_;
    QPushButton* retrieve_;
    QTreeWidget* results_;
    QLabel* status_;
    bool searching_ = false;
};

} // namespace lucent
