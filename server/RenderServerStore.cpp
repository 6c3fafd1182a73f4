// RenderServer: the store's series, scanned again when instances arrive (a
// C-STORE push, seen by DicomIntake, or an upload on the front door).
#include <QFile>
#include <QLoggingCategory>
#include <QMetaObject>

#include <map>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/store/StudyStore.h"
#include "server/HttpFrontDoor.h"
#include "server/RenderServer.h"
#include "server/UploadIngest.h"

namespace lucent::remote {
namespace {

Q_LOGGING_CATEGORY(lcStore, "lucent.server.store")

// The same files in the same order: the entry a client may still hold is kept,
// so that its loaded volume stays valid.
bool sameSlices(const SeriesEntry& a, const SeriesEntry& b) {
    if (a.slices.size() != b.slices.size() || a.file != b.file ||
        a.geometry.dims != b.geometry.dims) {
        return false;
    }
    for (std::size_t n = 0; n < a.slices.size(); ++n) {
        if (a.slices[n].file != b.slices[n].file || a.slices[n].frame != b.slices[n].frame) {
            return false;
        }
    }
    return true;
}

} // namespace

void RenderServer::rescanStore(std::function<void()> done) {
    if (scanRunning_) {
        scanAgain_ = true;
        if (done) {
            scanQueued_.push_back(std::move(done));
        }
        return;
    }
    if (done) {
        scanWaiters_.push_back(std::move(done));
    }
    scanRunning_ = true;
    scanPool_.start([this, root = options_.storeDir] {
        std::optional<SeriesList> found;
        try {
            found = scanStoreSeries(root).volumes;
        } catch (const std::exception&) {
            found.reset(); // the reason may name a patient's file: not logged
        }
        QMetaObject::invokeMethod(
            this,
            [this, found = std::move(found)] {
                if (found) {
                    setStoreSeries(*found);
                } else {
                    qCWarning(lcStore) << "the store could not be scanned; the list is unchanged";
                }
                scanRunning_ = false;
                for (auto& waiter : std::exchange(scanWaiters_, {})) {
                    waiter();
                }
                if (std::exchange(scanAgain_, false)) {
                    scanWaiters_ = std::exchange(scanQueued_, {});
                    rescanStore();
                }
            },
            Qt::QueuedConnection);
    });
}

void RenderServer::setStoreSeries(const SeriesList& storeSeries) {
    std::map<std::string, std::shared_ptr<const SeriesEntry>> before;
    for (const auto& s : series_) {
        before.emplace(s->id, s);
    }
    SeriesList kept;
    int changed = 0;
    for (const auto& s : storeSeries) {
        const auto old = before.find(s->id);
        if (old != before.end() && sameSlices(*old->second, *s)) {
            kept.push_back(old->second);
        } else {
            kept.push_back(s);
            copies_.erase(s->id); // a de-identified copy of fewer instances is stale
            ++changed;
        }
    }
    series_ = mergeServedSeries(kept, dataSeries_);
    if (changed > 0) {
        qCInfo(lcStore) << changed << "series new or grown in the store;" << series_.size()
                        << "served";
    }
}

void RenderServer::ingestUpload(QByteArray contentType, std::shared_ptr<const SpooledBody> body,
                                std::function<void(int, QByteArray)> reply) {
    scanPool_.start([this, root = options_.storeDir, contentType = std::move(contentType),
                     body = std::move(body), reply = std::move(reply)]() mutable {
        int status = 200;
        QByteArray answer;
        try {
            // Mapped, not read: the parts are views into the spooled file.
            QFile file(body->path());
            if (!file.open(QIODevice::ReadOnly)) {
                throw StoreError(body->path().toStdString() + ": cannot read the spooled upload (" +
                                 file.errorString().toStdString() + ")");
            }
            const qint64 size = file.size();
            const uchar* mapped = size > 0 ? file.map(0, size) : nullptr;
            if (size > 0 && mapped == nullptr) {
                throw StoreError(body->path().toStdString() + ": cannot map the spooled upload (" +
                                 file.errorString().toStdString() + ")");
            }
            const UploadSummary summary = storeUpload(
                root, contentType.toStdString(),
                std::string_view(reinterpret_cast<const char*>(mapped), std::size_t(size)));
            answer = QByteArray::fromStdString(nlohmann::json{
                         {"stored", summary.stored},
                         {"already_stored", summary.alreadyStored},
                         {"series",
                          summary.series}}.dump()) +
                     "\n";
        } catch (const UploadError& e) {
            status = e.status();
            answer = QByteArray(e.what()) + "\n";
        } catch (const std::exception&) {
            status = 500;
            answer = "the upload could not be stored on the server\n";
        }
        body.reset(); // the spooled file goes before the answer
        QMetaObject::invokeMethod(
            this,
            [this, status, answer, reply = std::move(reply)] {
                qCInfo(lcStore) << "upload answered" << status;
                if (status == 200) {
                    rescanStore([reply, answer] { reply(200, answer); });
                } else {
                    reply(status, answer);
                }
            },
            Qt::QueuedConnection);
    });
}

} // namespace lucent::remote
