// RenderServer: views, teaching sessions and their de-identified series.
#include <QLoggingCategory>
#include <QRandomGenerator>

#include "server/ClientConnection.h"
#include "server/DeidentifiedCopy.h"
#include "server/RenderServer.h"
#include "server/TeachingSession.h"
#include "server/ViewStream.h"

namespace lucent::remote {
namespace {

Q_LOGGING_CATEGORY(lcSessions, "lucent.server.sessions")

// 16 characters from 32: 80 random bits, not to be guessed.
QString newSessionId() {
    static constexpr char kAlphabet[] = "abcdefghijkmnpqrstuvwxyz23456789";
    QString id;
    for (int n = 0; n < 16; ++n) {
        id.append(QChar(kAlphabet[QRandomGenerator::system()->bounded(32)]));
    }
    return id;
}

} // namespace

void RenderServer::removeStaleCopies() {
    if (options_.storeDir.empty()) {
        return;
    }
    std::error_code error;
    const auto removed = std::filesystem::remove_all(options_.storeDir / "deidentified", error);
    if (error) {
        qCWarning(lcSessions) << "stale de-identified copies could not be removed:"
                              << error.message().c_str();
    } else if (removed > 0) {
        qCInfo(lcSessions) << "removed" << removed << "stale de-identified file(s)";
    }
}

void RenderServer::registerView(ViewStream* view) {
    views_.insert(view->id(), view);
}

void RenderServer::unregisterView(quint64 id) {
    views_.remove(id);
    std::erase_if(backgroundJobs_, [id](const RenderJob& job) { return job.view == id; });
}

TeachingSession* RenderServer::createSession(ClientConnection& presenter) {
    sessions_.removeIf([](const auto& entry) { return entry.value().isNull(); });
    if (sessions_.size() >= options_.maxSessions) {
        return nullptr;
    }
    QString id = newSessionId();
    while (sessions_.contains(id)) {
        id = newSessionId();
    }
    auto* session = new TeachingSession(id, presenter, *this, options_.maxSessionMembers, this);
    sessions_.insert(id, session);
    qCInfo(lcSessions) << "a session started;" << sessions_.size() << "running";
    return session;
}

TeachingSession* RenderServer::findSession(const QString& id) const {
    return sessions_.value(id);
}

void RenderServer::endSession(const QString& id) {
    invites_.sessionEnded(id);
    if (const QPointer<TeachingSession> session = sessions_.take(id)) {
        session->dismissAll();
        session->deleteLater();
    }
    qCInfo(lcSessions) << "a session ended;" << sessions_.size() << "running";
}

void RenderServer::deidentifiedCopy(const std::shared_ptr<const SeriesEntry>& original,
                                    QObject* context, CopyDone done) {
    if (const auto it = copies_.find(original->id); it != copies_.end()) {
        QMetaObject::invokeMethod(
            context, [done = std::move(done), copy = it->second] { done(copy, {}); },
            Qt::QueuedConnection);
        return;
    }
    auto& waiters = copyWaiters_[original->id];
    waiters.emplace_back(context, std::move(done));
    if (waiters.size() > 1) {
        return; // being made
    }
    copyPool_.start([this, original, store = options_.storeDir] {
        std::shared_ptr<const SeriesEntry> copy;
        QString error;
        try {
            if (store.empty()) {
                throw std::runtime_error("the server has no store for de-identified copies");
            }
            copy = makeDeidentifiedCopy(*original, store);
        } catch (const std::exception& e) {
            error = QString::fromUtf8(e.what());
        }
        QMetaObject::invokeMethod(
            this, [this, id = original->id, copy, error] { copyFinished(id, copy, error); },
            Qt::QueuedConnection);
    });
}

void RenderServer::copyFinished(const std::string& originalId,
                                std::shared_ptr<const SeriesEntry> copy, const QString& error) {
    if (copy) {
        copies_[originalId] = copy;
        qCInfo(lcSessions) << "a series was de-identified for a session";
    } else {
        qCWarning(lcSessions) << "de-identification failed"; // the reason may name a file
    }
    auto waiters = std::move(copyWaiters_[originalId]);
    copyWaiters_.erase(originalId);
    for (auto& [context, done] : waiters) {
        if (context) {
            done(copy, error);
        }
    }
}

} // namespace lucent::remote
