#include "core/pacs/PacsService.h"

#include <chrono>

#include <QElapsedTimer>
#include <QMetaObject>

#include "core/pacs/DicomWebClient.h"
#include "core/pacs/SeriesRetriever.h"
#include "core/pacs/StorageScp.h"
#include "core/store/StudyStore.h"

namespace lucent {

PacsService::PacsService(QObject* parent) : QObject(parent) {
    config_.storeFolder = PacsConfig::defaultStoreFolder();
    queries_.setMaxThreadCount(2);
    retrievals_.setMaxThreadCount(1); // one retrieval at a time, in order
}

PacsService::~PacsService() {
    cancelRetrievals();
    retrievals_.clear();
    retrievals_.waitForDone();
    queries_.waitForDone();
}

void PacsService::setConfig(const PacsConfig& config) {
    if (scp_ &&
        (config.callingAeTitle != config_.callingAeTitle ||
         config.storagePort != config_.storagePort || config.storeFolder != config_.storeFolder)) {
        scp_.reset(); // restarted with the new identity when needed
    }
    config_ = config;
}

void PacsService::post(std::function<void()> f) {
    QMetaObject::invokeMethod(this, std::move(f), Qt::QueuedConnection);
}

void PacsService::echo(const PacsNodeConfig& node) {
    const PacsSettings settings = config_.dimse();
    const int timeout = config_.timeoutSeconds;
    queries_.start([this, node, settings, timeout] {
        QElapsedTimer clock;
        clock.start();
        try {
            if (node.validate().isEmpty() && node.usesDicomWeb() && node.host.isEmpty()) {
                DicomWebService web = node.dicomWeb();
                web.timeoutSeconds = timeout;
                QueryFilter none;
                none.patientId = "LUCENT-ECHO-NO-SUCH-PATIENT";
                qidoSearch(web, QueryLevel::Study, none);
            } else if (const QString bad = node.validate(); !bad.isEmpty()) {
                throw PacsError(bad.toStdString());
            } else {
                lucent::echo(node.node(), settings);
            }
            const QString where = node.host.isEmpty()
                                      ? node.dicomWebUrl
                                      : QString::fromStdString(node.node().describe());
            const QString text = tr("%1 answered in %2 ms").arg(where).arg(clock.elapsed());
            post([this, text] { emit echoFinished(true, text); });
        } catch (const std::exception& e) {
            const QString text = QString::fromStdString(e.what());
            post([this, text] { emit echoFinished(false, text); });
        }
    });
}

void PacsService::query(const PacsNodeConfig& node, const QueryFilter& filter) {
    const PacsSettings settings = config_.dimse();
    const int timeout = config_.timeoutSeconds;
    queries_.start([this, node, filter, settings, timeout] {
        try {
            if (const QString bad = node.validate(); !bad.isEmpty()) {
                throw PacsError(bad.toStdString());
            }
            DicomWebService web = node.dicomWeb();
            web.timeoutSeconds = timeout;
            auto search = [&](QueryLevel level, const QueryFilter& f) {
                return node.usesDicomWeb() ? qidoSearch(web, level, f)
                                           : find(node.node(), settings, level, f);
            };
            std::vector<PacsStudyResult> results;
            for (QueryMatch& study : search(QueryLevel::Study, filter)) {
                QueryFilter inStudy;
                inStudy.studyUid = study.studyUid;
                inStudy.modalities = filter.modalities;
                PacsStudyResult r{std::move(study), {}};
                r.series = search(QueryLevel::Series, inStudy);
                results.push_back(std::move(r));
            }
            post([this, results = std::move(results)] { emit queryFinished(results); });
        } catch (const std::exception& e) {
            const QString text = QString::fromStdString(e.what());
            post([this, text] { emit queryFailed(text); });
        }
    });
}

QString PacsService::ensureStorageScp() {
    if (scp_) {
        return {};
    }
    try {
        scp_ = std::make_unique<StorageScp>(
            config_.storeFolder.toStdString(),
            StorageScpSettings{config_.callingAeTitle.toStdString(), config_.storagePort});
    } catch (const std::exception& e) {
        return QString::fromStdString(e.what());
    }
    return {};
}

void PacsService::retrieve(const PacsNodeConfig& node, const QList<SeriesRequest>& series) {
    std::stop_token stop;
    {
        const std::lock_guard lock(stopMutex_);
        stop = stop_.get_token();
    }
    QString problem = node.validate();
    if (problem.isEmpty()) {
        problem = config_.validate();
    }
    if (problem.isEmpty() && node.method == RetrievalMethod::CMove) {
        problem = ensureStorageScp();
    }
    const PacsSettings settings = config_.dimse();
    const std::string root = config_.storeFolder.toStdString();
    const std::string destination = config_.callingAeTitle.toStdString();
    const int timeout = config_.timeoutSeconds;
    for (const SeriesRequest& request : series) {
        emit retrievalQueued(request.seriesUid, request.label);
        if (!problem.isEmpty()) {
            emit retrievalFinished(request.seriesUid, false, problem);
            continue;
        }
        ++pending_;
        retrievals_.start([=, this] {
            const QString uid = request.seriesUid;
            QString message;
            bool ok = false;
            QString arrived;
            try {
                if (stop.stop_requested()) {
                    throw PacsError("cancelled before it started");
                }
                StudyStore store(root);
                RetrieveControl control;
                control.stop = stop;
                control.onProgress = [&](int done, int total) {
                    post([this, uid, done, total] {
                        emit retrievalProgress(uid, done, std::max(0, total - done), 0);
                    });
                };
                const std::string study = request.studyUid.toStdString();
                const std::string seriesUid = uid.toStdString();
                DicomWebService web = node.dicomWeb();
                web.timeoutSeconds = timeout;
                const RetrieveResult r =
                    node.method == RetrievalMethod::Wado
                        ? wadoRetrieveSeries(web, study, seriesUid, store, control)
                    : node.method == RetrievalMethod::CMove
                        ? moveSeries(node.node(), settings, destination, study, seriesUid, store,
                                     control)
                        : retrieveSeries(node.node(), settings, study, seriesUid, store, control);
                const int completed = r.received + r.alreadyStored;
                post([this, uid, r, completed] {
                    emit retrievalProgress(
                        uid, completed, std::max(0, r.expected - completed - r.failed), r.failed);
                });
                ok = r.complete;
                message = ok ? tr("complete: %1 arrived, %2 already stored")
                                   .arg(r.received)
                                   .arg(r.alreadyStored)
                             : tr("incomplete: %1 of %2 stored, %3 failed")
                                   .arg(completed)
                                   .arg(r.expected)
                                   .arg(r.failed);
                if (ok) {
                    arrived = QString::fromStdString(r.folder.string());
                }
            } catch (const std::exception& e) {
                message = QString::fromStdString(e.what());
            }
            const bool announce = request.announce;
            post([this, uid, ok, message, arrived, announce] {
                --pending_;
                if (!arrived.isEmpty()) {
                    emit seriesStored(arrived, uid);
                }
                emit retrievalFinished(uid, ok, message);
                if (!arrived.isEmpty() && announce) {
                    emit seriesArrived(arrived, uid);
                }
                if (pending_ == 0) {
                    emit allRetrievalsFinished();
                }
            });
        });
    }
    if (pending_ == 0) {
        emit allRetrievalsFinished(); // nothing could start
    }
}

void PacsService::cancelRetrievals() {
    const std::lock_guard lock(stopMutex_);
    stop_.request_stop();
    stop_ = std::stop_source(); // later retrievals start afresh
}

} // namespace lucent
