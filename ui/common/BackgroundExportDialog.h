#pragma once
// A non-modal dialog that exports on a worker thread of its own: a progress
// bar, a status line, and Export and Close buttons. While the export runs,
// Close reads Cancel and asks the worker to stop (the job checks its stop
// token). Done, failed and cancelled each end with the job's message in the
// status line and exportFinished. The exports of the movie (ui/app) and of
// stored series (ui/pacs) derive from it: they give the form and the job.

#include <QDialog>
#include <QString>

#include <exception>
#include <optional>
#include <stop_token>
#include <thread>
#include <utility>

class QFormLayout;
class QLabel;
class QProgressBar;
class QPushButton;

namespace lucent {

// How an export job ended: ok is false after an error or a cancel; the message
// says what was written or why not.
struct ExportOutcome {
    bool ok = false;
    QString message;
};

class BackgroundExportDialog : public QDialog {
    Q_OBJECT

public:
    ~BackgroundExportDialog() override; // cancels a running export and waits for it

    QPushButton* exportButton() const { return export_; }
    // Cancel while exporting, Close otherwise.
    QPushButton* closeButton() const { return close_; }
    QLabel* status() const { return status_; }
    QProgressBar* progressBar() const { return bar_; }
    bool running() const { return running_; }

signals:
    void progressed(int done, int total);
    // ok is false after an error or a cancel; message says what was written or why not.
    void exportFinished(bool ok, const QString& message);

protected:
    explicit BackgroundExportDialog(QWidget* parent);

    // Adds the progress bar, the status line and the buttons as the last rows of
    // `form`. Once, at the end of the subclass's constructor, so that they come
    // last in the tab order (the widgets are made here).
    void addExportRows(QFormLayout* form);

    // Export was pressed and nothing runs: check the form, then startJob(), or
    // say in the status line what is wrong.
    virtual void start() = 0;

    // Runs `job` (callable with a std::stop_token, returning ExportOutcome) on
    // the worker thread; `doing` is the status meanwhile. An exception from the
    // job is a failure with its what(). The job and all it owns (an unfinished
    // file, say) are gone before the outcome is reported. The job runs until
    // this class's destructor: it must not reach the subclass's members.
    template <class Job> void startJob(const QString& doing, Job job);

    // From the worker thread: `done` of `total`, shown by the bar and reported
    // by progressed().
    void reportProgress(int done, int total);

private:
    void begin(const QString& doing);
    // From the worker thread: done() on the dialog's thread.
    void reportOutcome(ExportOutcome outcome);
    void done(const ExportOutcome& outcome);

    QProgressBar* bar_ = nullptr;
    QLabel* status_ = nullptr;
    QPushButton* export_ = nullptr;
    QPushButton* close_ = nullptr;
    bool running_ = false;
    std::jthread worker_;
};

template <class Job> void BackgroundExportDialog::startJob(const QString& doing, Job job) {
    begin(doing);
    worker_ = std::jthread(
        [this, owned = std::optional<Job>(std::move(job))](std::stop_token stop) mutable {
            ExportOutcome outcome;
            try {
                outcome = (*owned)(stop);
            } catch (const std::exception& e) {
                outcome = {false, QString::fromStdString(e.what())};
            }
            owned.reset();
            reportOutcome(std::move(outcome));
        });
}

} // namespace lucent
