// PacsService::send: instances to a node on the retrieval thread, one
// transfer after the other, with the retrievals' signals.
#include <filesystem>

#include "core/pacs/InstanceSender.h"
#include "core/pacs/PacsService.h"

namespace lucent {

std::stop_token PacsService::stopToken() {
    const std::lock_guard lock(stopMutex_);
    return stop_.get_token();
}

void PacsService::finishOne(const QString& key, bool ok, const QString& message) {
    --pending_;
    emit retrievalFinished(key, ok, message);
    if (pending_ == 0) {
        emit allRetrievalsFinished();
    }
}

void PacsService::send(const PacsNodeConfig& node, const QString& key, const QString& label,
                       const QStringList& files) {
    emit retrievalQueued(key, label);
    QString problem = node.validate();
    if (problem.isEmpty()) {
        problem = config_.validate();
    }
    if (!problem.isEmpty()) {
        emit retrievalFinished(key, false, problem);
        return;
    }
    const std::stop_token stop = stopToken();
    const PacsSettings settings = config_.dimse();
    DicomWebService web = node.dicomWeb();
    web.timeoutSeconds = config_.timeoutSeconds;
    ++pending_;
    retrievals_.start([=, this] {
        bool ok = false;
        QString message;
        try {
            if (stop.stop_requested()) {
                throw PacsError("cancelled before it started");
            }
            std::vector<InstanceHeader> instances;
            for (const QString& f : files) {
                instances.push_back(readInstanceHeader(f.toStdString()));
            }
            SendControl control;
            control.stop = stop;
            control.onProgress = [&](int done, int total) {
                post([this, key, done, total] {
                    emit retrievalProgress(key, done, total - done, 0);
                });
            };
            const SendResult r = node.usesDicomWeb()
                                     ? sendByStow(web, instances, control)
                                     : sendByCStore(node.node(), settings, instances, control);
            for (const SentInstance& s : r.instances) {
                if (s.outcome == SentInstance::Outcome::Failed ||
                    s.outcome == SentInstance::Outcome::NotSent) {
                    post([this, key, file = QString::fromStdString(s.file.filename().string()),
                          why = QString::fromStdString(s.message)] {
                        emit instanceNotStored(key, file, why);
                    });
                }
            }
            using O = SentInstance::Outcome;
            const int stored = r.count(O::Stored) + r.count(O::StoredWithWarning);
            const int failed = r.count(O::Failed);
            post([this, key, stored, failed, r] {
                emit retrievalProgress(key, stored, r.count(O::NotSent), failed);
            });
            ok = r.allStored();
            message = ok ? tr("sent: %1 stored").arg(stored)
                      : r.cancelled
                          ? tr("cancelled: %1 of %2 stored").arg(stored).arg(r.instances.size())
                          : tr("%1 of %2 stored, %3 failed")
                                .arg(stored)
                                .arg(r.instances.size())
                                .arg(failed);
        } catch (const std::exception& e) {
            message = QString::fromStdString(e.what());
        }
        post([this, key, ok, message] { finishOne(key, ok, message); });
    });
}

} // namespace lucent
