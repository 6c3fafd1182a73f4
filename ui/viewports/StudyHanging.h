#pragma once

#include <memory>
#include <set>
#include <thread>
#include <vector>

#include <QElapsedTimer>
#include <QObject>
#include <QString>

#include "core/hanging/HangingProtocol.h"

namespace lucent {

class PacsService;
class PriorsForStudy;
class SeriesSession;
class ViewportWorkspace;

// Hangs a study when it opens: the series of the opened path and the patient's other
// studies in the local store become HangingSeries (current study first, priors by
// date), the shipped and the user's hanging protocols are ranked on them, and the
// best is applied to the viewport grid (its name in the grid's caption). When the
// protocol asks for priors that are not here, PriorsForStudy finds the comparable
// one on every PACS node and fetches it; when it arrives the protocol is applied
// again with it; a prior in another Frame of Reference is then registered with the
// current study by itself (ViewportRegistration). The "MPR 2x2" set of one series is the MPR layout
// of the main window (mprRequested). Keys step through protocols and their viewport sets.
class StudyHanging : public QObject {
    Q_OBJECT

public:
    StudyHanging(ViewportWorkspace* workspace, PacsService* service, QString userFolder,
                 QObject* parent = nullptr);
    ~StudyHanging() override;

    // Hangs the study of `path` (a folder, DICOMDIR or a study folder of the store):
    // the newest study there is the current one.
    void open(const QString& path);

    // Reads the protocols again (after one was saved); returns the errors, per file.
    QStringList reloadProtocols();
    const std::vector<HangingProtocol>& protocols() const { return protocols_; }
    // The ranking of the study open now (best first) and the one applied.
    const std::vector<HangingResult>& ranking() const { return ranking_; }
    const HangingResult* applied() const;
    int appliedRank() const { return rank_; }

    // Steps to the next (+1) or previous (-1) applicable protocol, or viewport set.
    void stepProtocol(int step);
    void stepViewportSet(int step);
    // Applies the ranking's entry `rank` with viewport set `set`.
    void apply(int rank, int set);

    // Writes the grid as it is now as a protocol named `name` in the user's folder;
    // returns the file, or an empty string with the reason in `error`.
    QString saveLayout(const QString& name, QString* error);

    PriorsForStudy* priors() const { return priors_.get(); }
    const std::vector<HangingSeries>& series() const { return series_; }

signals:
    // The protocol is the MPR layout of one series: show it in the main window.
    void mprRequested(const QString& path, const QString& series);
    // Every viewport the protocol fills shows its series (priors included when asked
    // for and found): ms since open().
    void hung(const QString& protocol, qint64 ms);
    void message(const QString& text, int timeoutMs);

private:
    // Scans path (and, with a store folder, the patient's studies in the store) on a
    // worker; scanned() merges the series on the GUI thread.
    // arrivedOrder: the prior whose folder this is (0: none).
    void scan(const QString& path, const QString& storeFolder, bool rerank, int arrivedOrder = 0);
    void scanned(std::vector<HangingSeries> found, bool rerank);
    // `set`, or the protocol's first viewport set that shows a prior when `set` shows
    // none and a prior is here: a follow-up read starts against its prior.
    int setShowingPriors(int rank, int set) const;
    void show(const HangingResult& result);
    void viewportShown();
    void registerPriors(const HangingResult& result);
    void priorReady(int order, const QString& folder);
    // A prior asked for is not coming (none, or its fetch failed).
    void priorGone(int order);

    ViewportWorkspace* workspace_;
    PacsService* service_;
    QString userFolder_;
    std::unique_ptr<PriorsForStudy> priors_;
    std::vector<HangingProtocol> protocols_;
    std::vector<HangingSeries> series_;
    std::vector<HangingResult> ranking_;
    int rank_ = -1;
    int set_ = 0;
    QString studyUid_;
    QString patientId_;
    QElapsedTimer clock_;
    std::set<QString> waiting_;  // viewports (by object name) not yet showing their series
    std::set<int> priorsWanted_; // study orders asked of PriorsForStudy, not yet arrived
    bool reported_ = false;
    std::uint64_t generation_ = 0; // a scan of an older open() is dropped
    std::vector<std::jthread> scans_;
};

} // namespace lucent
