#pragma once
// The patient's other studies, found and fetched by themselves when a study opens: the
// local store and every configured PACS node are asked (C-FIND at study and series level
// by Patient ID, or QIDO-RS for a DICOMweb node) on a worker thread; the studies become
// one list (PriorSelection's rule numbers the comparable priors), and each prior the
// hanging protocol asks for that is not complete in the store is retrieved in the
// background through PacsService (its progress list and cancel; instances and series
// already stored are not fetched again). Results come as signals on the GUI thread.

#include <map>
#include <set>
#include <thread>
#include <vector>

#include <QList>
#include <QObject>
#include <QString>
#include <QStringList>

#include "core/pacs/PacsConfig.h"
#include "core/pacs/PriorSelection.h"

namespace lucent {

class PacsService;

class PriorsForStudy : public QObject {
    Q_OBJECT

public:
    explicit PriorsForStudy(PacsService& service, QObject* parent = nullptr);
    ~PriorsForStudy() override; // waits for a lookup in flight (bounded by the PACS timeout)

    // Looks up the patient's studies; then each prior of `orders` (1: the most recent
    // comparable one) comes as priorReady (fetched first when the store lacks some of
    // it) or noPrior. A new start drops what an earlier one had not reported.
    void start(const CurrentStudy& current, const QList<int>& orders);
    // Fetches every series of a listed study that the store lacks (false when no node
    // has it, or it is being fetched); studyFetched or fetchFailed follows.
    bool fetch(const QString& studyUid);
    // Cancels the lookup's reports and the service's retrievals.
    void cancel();

    const CurrentStudy& current() const { return current_; }
    // Newest first; empty until studiesFound.
    const std::vector<PatientStudy>& studies() const { return studies_; }
    const PatientStudy* study(const QString& studyUid) const;
    // The nodes that could not be asked, with why ("name: reason").
    const QStringList& nodeErrors() const { return nodeErrors_; }
    bool lookingUp() const { return lookingUp_; }
    bool isFetching(const QString& studyUid) const { return fetches_.count(studyUid) > 0; }
    // The prior number of a listed study (0 for the current one, -1 for others).
    int priorOrder(const QString& studyUid) const;
    const QList<PacsNodeConfig>& nodes() const { return config_.nodes; }

signals:
    void lookupStarted();
    void studiesFound();
    void fetchStarted(const QString& studyUid);
    void fetchProgress(const QString& studyUid, int done, int total);
    // Every series asked for is complete in the store (study folder, its series).
    void studyFetched(const QString& studyUid, const QString& folder,
                      const QStringList& seriesUids);
    // No series of the study arrived (then noPrior too, when it was a prior asked
    // for), or some did not (after studyFetched).
    void fetchFailed(const QString& studyUid, const QString& why);
    // A prior the protocol asked for is complete in the store.
    void priorReady(int order, const QString& folder, const QStringList& seriesUids);
    void noPrior(int order, const QString& reason);

private:
    struct Fetch {
        std::set<QString> pending; // series UIDs not yet finished
        std::map<QString, int> done;
        int total = 0;
        QStringList arrived;
        QStringList failures;
        QString folder;
    };
    struct Lookup {
        std::vector<PatientStudy> studies;
        QStringList nodeErrors;
    };
    static Lookup lookUp(const PacsConfig& config, const CurrentStudy& current);
    void found(Lookup lookup, const QList<int>& orders);
    void seriesFinished(const QString& seriesUid, bool ok, const QString& message);
    void fetchDone(const QString& studyUid, Fetch fetch);
    void markStored(const QString& studyUid, const QString& folder, const QStringList& seriesUids);
    QString noPriorReason() const;

    PacsService& service_;
    PacsConfig config_;
    CurrentStudy current_;
    std::vector<PatientStudy> studies_;
    QStringList nodeErrors_;
    bool lookingUp_ = false;
    std::map<QString, Fetch> fetches_;    // by study UID
    std::map<QString, int> ordersWanted_; // study UID -> prior order asked for
    std::uint64_t generation_ = 0;
    std::vector<std::jthread> lookups_;
};

} // namespace lucent
