#pragma once
// Progress of the queued and running transfers, one row per retrieved series
// or per send (completed, remaining, failed, status; below a send, each
// instance the node did not store, with the reason), with a Cancel button.

#include <QWidget>

class QPushButton;
class QTreeWidget;
class QTreeWidgetItem;

namespace lucent {

class PacsService;

class RetrievalProgress : public QWidget {
    Q_OBJECT

public:
    enum Column { Series, Completed, Remaining, Failed, Status };

    explicit RetrievalProgress(PacsService* service, QWidget* parent = nullptr);

    QTreeWidget* list() const { return list_; }
    QPushButton* cancelButton() const { return cancel_; }
    // The row of a series; nullptr when it was never queued.
    QTreeWidgetItem* row(const QString& seriesUid) const;

private:
    void queued(const QString& seriesUid, const QString& label);
    void progress(const QString& seriesUid, int completed, int remaining, int failed);
    void finished(const QString& seriesUid, bool ok, const QString& message);

    PacsService* service_;
    QTreeWidget* list_;
    QPushButton* cancel_;
};

} // namespace lucent
