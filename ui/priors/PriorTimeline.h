#pragma once

#include <QString>
#include <QWidget>

class QLabel;
class QPushButton;
class QTreeWidget;
class QTreeWidgetItem;

namespace lucent {

class PriorsForStudy;
struct CurrentStudy;
struct PatientStudy;

// The series of a study a reader looks at first: of the current study's modality, the
// one with the most images (not the localizer or the dose report).
QString readingSeries(const PatientStudy& study, const CurrentStudy& current);

// The patient's studies as a timeline, newest first: the study read now, its priors
// numbered (the comparable ones), the rest greyed; where each is (store, PACS nodes)
// and what happens to it (complete in the store, on PACS, fetching n of m, failed).
// Activating a study in the store opens it; one on a PACS only is fetched first, then
// opened. The nodes that could not be asked are named above the list.
class PriorTimeline : public QWidget {
    Q_OBJECT

public:
    explicit PriorTimeline(PriorsForStudy& priors, QWidget* parent = nullptr);

    QTreeWidget* list() const { return list_; }
    // Opens (or fetches, then opens) the study of a row.
    void activate(const QString& studyUid);

signals:
    // A study complete in the store, to show: its folder and the series to read.
    void openStudy(const QString& folder, const QString& seriesUid);

private:
    void rebuild();
    void setState(const QString& studyUid, const QString& state);
    QTreeWidgetItem* itemOf(const QString& studyUid) const;

    PriorsForStudy& priors_;
    QLabel* heading_;
    QTreeWidget* list_;
    QPushButton* cancel_;
    QString openWhenFetched_;
};

} // namespace lucent
