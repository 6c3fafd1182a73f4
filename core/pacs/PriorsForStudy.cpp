#include "core/pacs/PriorsForStudy.h"

#include <algorithm>
#include <filesystem>

#include <QMetaObject>

#include "core/pacs/DicomWebClient.h"
#include "core/pacs/PacsService.h"
#include "core/store/StudyStore.h"

namespace lucent {

PriorsForStudy::PriorsForStudy(PacsService& service, QObject* parent)
    : QObject(parent), service_(service) {
    connect(&service_, &PacsService::retrievalFinished, this, &PriorsForStudy::seriesFinished);
    connect(&service_, &PacsService::seriesStored, this,
            [this](const QString& folder, const QString& seriesUid) {
                for (auto& [study, fetch] : fetches_) {
                    if (fetch.pending.count(seriesUid)) {
                        fetch.folder = QString::fromStdString(
                            std::filesystem::path(folder.toStdString()).parent_path().string());
                    }
                }
            });
    connect(&service_, &PacsService::retrievalProgress, this,
            [this](const QString& seriesUid, int completed, int, int) {
                for (auto& [study, fetch] : fetches_) {
                    if (fetch.pending.count(seriesUid)) {
                        fetch.done[seriesUid] = completed;
                        int done = 0;
                        for (const auto& [uid, n] : fetch.done) {
                            done += n;
                        }
                        emit fetchProgress(study, done, std::max(done, fetch.total));
                    }
                }
            });
}

PriorsForStudy::~PriorsForStudy() {
    ++generation_;
    lookups_.clear(); // joins; a lookup posts only while this object exists
}

PriorsForStudy::Lookup PriorsForStudy::lookUp(const PacsConfig& config,
                                              const CurrentStudy& current) {
    Lookup out;
    if (current.patientId.empty()) {
        // An empty ID would match every patient on a PACS.
        out.nodeErrors << tr("the study has no Patient ID: no other study can be its prior");
        return out;
    }
    try {
        if (!config.storeFolder.isEmpty() &&
            std::filesystem::exists(config.storeFolder.toStdString())) {
            const StudyStore store(config.storeFolder.toStdString());
            out.studies = studiesInStore(store.listSeries(), current.patientId);
        }
    } catch (const std::exception& e) {
        out.nodeErrors << QStringLiteral("store: %1").arg(QString::fromUtf8(e.what()));
    }
    const PacsSettings settings = config.dimse();
    for (int n = 0; n < config.nodes.size(); ++n) {
        const PacsNodeConfig& node = config.nodes[n];
        try {
            if (const QString bad = node.validate(); !bad.isEmpty()) {
                throw PacsError(bad.toStdString());
            }
            DicomWebService web = node.dicomWeb();
            web.timeoutSeconds = config.timeoutSeconds;
            auto search = [&](QueryLevel level, const QueryFilter& f) {
                return node.usesDicomWeb() ? qidoSearch(web, level, f)
                                           : find(node.node(), settings, level, f);
            };
            QueryFilter byPatient;
            byPatient.patientId = current.patientId;
            for (const QueryMatch& study : search(QueryLevel::Study, byPatient)) {
                if (study.patientId != current.patientId) {
                    continue; // a PACS that matches IDs loosely (wildcards, case)
                }
                QueryFilter inStudy;
                inStudy.studyUid = study.studyUid;
                mergeNodeStudies(out.studies, n, study, search(QueryLevel::Series, inStudy));
            }
        } catch (const std::exception& e) {
            out.nodeErrors << QStringLiteral("%1: %2").arg(node.name, QString::fromUtf8(e.what()));
        }
    }
    orderPriors(out.studies, current);
    return out;
}

void PriorsForStudy::start(const CurrentStudy& current, const QList<int>& orders) {
    const std::uint64_t generation = ++generation_;
    current_ = current;
    config_ = service_.config();
    studies_.clear();
    nodeErrors_.clear();
    ordersWanted_.clear();
    lookingUp_ = true;
    emit lookupStarted();
    lookups_.emplace_back([this, generation, orders, config = config_, current] {
        Lookup lookup = lookUp(config, current);
        QMetaObject::invokeMethod(
            this,
            [this, generation, orders, lookup = std::move(lookup)]() mutable {
                if (generation == generation_) {
                    found(std::move(lookup), orders);
                }
            },
            Qt::QueuedConnection);
    });
}

QString PriorsForStudy::noPriorReason() const {
    QString reason = tr("no earlier %1%2 study of patient %3 in the store or on %4 PACS node(s)")
                         .arg(QString::fromStdString(current_.modality),
                              current_.bodyPart.empty()
                                  ? QString()
                                  : QStringLiteral(" ") + QString::fromStdString(current_.bodyPart),
                              QString::fromStdString(current_.patientId))
                         .arg(config_.nodes.size());
    if (!nodeErrors_.isEmpty()) {
        reason += tr(" (not asked: %1)").arg(nodeErrors_.join(QStringLiteral("; ")));
    }
    return reason;
}

void PriorsForStudy::found(Lookup lookup, const QList<int>& orders) {
    lookingUp_ = false;
    studies_ = std::move(lookup.studies);
    nodeErrors_ = std::move(lookup.nodeErrors);
    emit studiesFound();
    for (const int order : orders) {
        const auto prior = std::find_if(studies_.begin(), studies_.end(),
                                        [&](const PatientStudy& s) { return s.order == order; });
        if (prior == studies_.end()) {
            emit noPrior(order, noPriorReason());
            continue;
        }
        const QString uid = QString::fromStdString(prior->studyUid);
        ordersWanted_[uid] = order;
        if (prior->completeInStore()) {
            QStringList series;
            for (const PatientSeries& s : prior->series) {
                series << QString::fromStdString(s.seriesUid);
            }
            emit priorReady(order, QString::fromStdString(prior->storeFolder), series);
        } else if (!isFetching(uid) && !fetch(uid)) {
            emit noPrior(order, tr("prior %1 (%2) is on no reachable PACS node")
                                    .arg(order)
                                    .arg(QString::fromStdString(describeStudy(*prior))));
        }
    }
}

bool PriorsForStudy::fetch(const QString& studyUid) {
    const PatientStudy* s = study(studyUid);
    if (s == nullptr || s->nodes.empty() || isFetching(studyUid) ||
        s->nodes.front() >= config_.nodes.size()) {
        return false;
    }
    Fetch fetch;
    QList<SeriesRequest> requests;
    const QString label = QString::fromStdString(describeStudy(*s));
    for (const PatientSeries& series : s->series) {
        const QString uid = QString::fromStdString(series.seriesUid);
        if (series.completeInStore) {
            fetch.arrived << uid; // what is in the store already is not fetched again
            continue;
        }
        fetch.pending.insert(uid);
        fetch.total += series.instances;
        SeriesRequest r{studyUid, uid,
                        tr("Prior %1: %2").arg(label, QString::fromStdString(series.description)),
                        false};
        requests << r;
    }
    fetch.folder = QString::fromStdString(s->storeFolder);
    if (requests.isEmpty()) {
        return false;
    }
    fetches_[studyUid] = std::move(fetch);
    emit fetchStarted(studyUid);
    service_.retrieve(config_.nodes[s->nodes.front()], requests);
    return true;
}

void PriorsForStudy::cancel() {
    ++generation_;
    lookingUp_ = false;
    service_.cancelRetrievals();
}

void PriorsForStudy::seriesFinished(const QString& seriesUid, bool ok, const QString& message) {
    for (auto it = fetches_.begin(); it != fetches_.end(); ++it) {
        Fetch& f = it->second;
        if (f.pending.erase(seriesUid) == 0) {
            continue;
        }
        (ok ? f.arrived : f.failures) << (ok ? seriesUid : message);
        if (f.pending.empty()) {
            const QString study = it->first;
            Fetch done = std::move(f);
            fetches_.erase(it);
            fetchDone(study, std::move(done));
        }
        return;
    }
}

void PriorsForStudy::fetchDone(const QString& studyUid, Fetch fetch) {
    const auto wanted = ordersWanted_.find(studyUid);
    if (fetch.arrived.isEmpty() || fetch.folder.isEmpty()) {
        const QString why = fetch.failures.isEmpty() ? tr("nothing arrived")
                                                     : fetch.failures.join(QStringLiteral("; "));
        emit fetchFailed(studyUid, why);
        if (wanted != ordersWanted_.end()) {
            emit noPrior(wanted->second, tr("not fetched: %1").arg(why));
        }
        return;
    }
    markStored(studyUid, fetch.folder, fetch.arrived);
    emit studyFetched(studyUid, fetch.folder, fetch.arrived);
    if (wanted != ordersWanted_.end()) {
        emit priorReady(wanted->second, fetch.folder, fetch.arrived);
    }
    if (!fetch.failures.isEmpty()) {
        // The series that came are worth reading; the rest are reported.
        emit fetchFailed(studyUid, tr("%1 series not fetched: %2")
                                       .arg(fetch.failures.size())
                                       .arg(fetch.failures.join(QStringLiteral("; "))));
    }
}

void PriorsForStudy::markStored(const QString& studyUid, const QString& folder,
                                const QStringList& seriesUids) {
    for (PatientStudy& s : studies_) {
        if (QString::fromStdString(s.studyUid) != studyUid) {
            continue;
        }
        for (PatientSeries& series : s.series) {
            if (seriesUids.contains(QString::fromStdString(series.seriesUid))) {
                series.completeInStore = true;
            }
        }
        s.storeFolder = folder.toStdString();
    }
}

const PatientStudy* PriorsForStudy::study(const QString& studyUid) const {
    const std::string uid = studyUid.toStdString();
    const auto found = std::find_if(studies_.begin(), studies_.end(),
                                    [&](const PatientStudy& s) { return s.studyUid == uid; });
    return found == studies_.end() ? nullptr : &*found;
}

int PriorsForStudy::priorOrder(const QString& studyUid) const {
    const PatientStudy* s = study(studyUid);
    return s == nullptr ? -1 : s->order;
}

} // namespace lucent
