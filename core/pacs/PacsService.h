#pragma once
// PACS operations for the workstation, off the GUI thread: echo and query on a
// thread pool, retrievals one after the other on a thread of their own. Every
// result comes back as a signal on the GUI thread. Cancel stops the running
// retrieval (the association or HTTP request is aborted) and the queued ones.

#include <memory>
#include <mutex>
#include <stop_token>
#include <vector>

#include <QObject>
#include <QString>
#include <QThreadPool>

#include "core/pacs/DimseQuery.h"
#include "core/pacs/PacsConfig.h"

namespace lucent {

class StorageScp;

// A study found by a query, with its series.
struct PacsStudyResult {
    QueryMatch study;
    std::vector<QueryMatch> series;
};

struct SeriesRequest {
    QString studyUid;
    QString seriesUid;
    QString label; // for the progress list
    // False for a fetch in the background (a prior): seriesArrived is not emitted, so
    // nothing opens it in the main window; seriesStored still is.
    bool announce = true;
};

class PacsService : public QObject {
    Q_OBJECT

public:
    explicit PacsService(QObject* parent = nullptr);
    ~PacsService() override; // cancels and waits for the running operations

    // Where retrievals store, our AE title, storage SCP port and timeouts.
    void setConfig(const PacsConfig& config);
    const PacsConfig& config() const { return config_; }

    void echo(const PacsNodeConfig& node);
    // Studies matching the filter, each with its series (C-FIND or QIDO-RS).
    void query(const PacsNodeConfig& node, const QueryFilter& filter);
    // Queues the series for retrieval by the node's method.
    void retrieve(const PacsNodeConfig& node, const QList<SeriesRequest>& series);
    // Queues files for sending to the node: C-STORE, or STOW-RS for a DICOMweb
    // node. Progress and the end come as the retrieval signals, keyed by `key`
    // (one row of the transfers list); each instance the node did not store
    // also as instanceNotStored. Cancel stops it between instances.
    void send(const PacsNodeConfig& node, const QString& key, const QString& label,
              const QStringList& files);
    void cancelRetrievals();
    int pendingRetrievals() const { return pending_; }

signals:
    void echoFinished(bool ok, const QString& message);
    void queryFinished(const std::vector<lucent::PacsStudyResult>& results);
    void queryFailed(const QString& message);
    void retrievalQueued(const QString& seriesUid, const QString& label);
    void retrievalProgress(const QString& seriesUid, int completed, int remaining, int failed);
    void retrievalFinished(const QString& seriesUid, bool ok, const QString& message);
    // A series asked for with `announce` is complete in the store: its folder, ready to open.
    void seriesArrived(const QString& folder, const QString& seriesUid);
    // Any series retrieved is complete in the store (announced or not).
    void seriesStored(const QString& folder, const QString& seriesUid);
    void allRetrievalsFinished();
    void instanceNotStored(const QString& key, const QString& file, const QString& message);

private:
    void post(std::function<void()> f); // runs f on the GUI thread, if this still exists
    std::stop_token stopToken();
    void finishOne(const QString& key, bool ok, const QString& message);
    QString ensureStorageScp();

    PacsConfig config_;
    QThreadPool queries_;
    QThreadPool retrievals_;
    std::mutex stopMutex_;
    std::stop_source stop_;
    int pending_ = 0;
    std::unique_ptr<StorageScp> scp_;
};

} // namespace lucent
