#include "ui/viewports/SeriesLibrary.h"

#include <QMetaObject>

#include "core/dicom/StackLoader.h"
#include "core/io/Catalog.h"
#include "core/io/DisplayedSeries.h"
#include "core/pet/PetDisplay.h"
#include "ui/viewports/SeriesSession.h"

namespace lucent {

SeriesLibrary::SeriesLibrary(QObject* parent) : QObject(parent) {}

SeriesLibrary::~SeriesLibrary() {
    for (Pending& p : pending_) {
        p.worker.request_stop();
    }
    pending_.clear(); // joins
}

SeriesSession* SeriesLibrary::find(const QString& path, const QString& series) const {
    for (SeriesSession* s : sessions_) {
        if (s->path() == path &&
            (s->series() == series || (!series.isEmpty() && s->seriesUid() == series))) {
            return s;
        }
    }
    return nullptr;
}

SeriesSession* SeriesLibrary::findUid(const std::string& seriesUid) const {
    for (SeriesSession* s : sessions_) {
        if (!seriesUid.empty() && s->info().seriesUid == seriesUid) {
            return s;
        }
    }
    return nullptr;
}

SeriesSession* SeriesLibrary::adopt(std::shared_ptr<const Volume> volume, const QString& path,
                                    const QString& series) {
    if (SeriesSession* known = find(path, series)) {
        return known;
    }
    if (SeriesSession* known = findUid(volume->seriesUid)) {
        return known;
    }
    auto* session = new SeriesSession(std::move(volume), path, series, this);
    sessions_.push_back(session);
    return session;
}

void SeriesLibrary::request(const QString& path, const QString& series) {
    if (SeriesSession* known = find(path, series)) {
        QMetaObject::invokeMethod(
            this, [this, path, series, known] { emit ready(path, series, known); },
            Qt::QueuedConnection);
        return;
    }
    for (const Pending& p : pending_) {
        if (p.path == path && p.series == series) {
            return;
        }
    }
    Pending& p = pending_.emplace_back();
    p.path = path;
    p.series = series;
    p.worker = std::jthread([this, path, series](std::stop_token stop) {
        std::shared_ptr<Volume> volume;
        std::shared_ptr<ImageStack> stack;
        QString error;
        try {
            LoadControl control;
            control.stop = stop;
            const Catalog catalog = scanPath(path.toStdString(), control);
            const SeriesEntry* entry =
                series.isEmpty() ? catalog.defaultEntry() : catalog.find(series.toStdString());
            if (entry == nullptr && series.isEmpty() && !catalog.series.empty()) {
                entry = &catalog.series.front(); // only images: the first stack
            }
            if (entry == nullptr) {
                throw LoadError(path.toStdString() + ": no series " + series.toStdString());
            }
            if (entry->kind == SeriesKind::Volume) {
                volume = std::make_shared<Volume>(loadDisplayedSeries(*entry, control));
            } else {
                stack = std::make_shared<ImageStack>(loadStack(*entry, control));
            }
        } catch (const LoadCancelled&) {
            return;
        } catch (const std::exception& e) {
            error = QString::fromUtf8(e.what());
        }
        QMetaObject::invokeMethod(
            this,
            [this, path, series, volume, stack, error] {
                finish(path, series, volume, stack, error);
            },
            Qt::QueuedConnection);
    });
}

void SeriesLibrary::finish(const QString& path, const QString& series,
                           std::shared_ptr<Volume> volume, std::shared_ptr<ImageStack> stack,
                           const QString& error) {
    for (auto it = pending_.begin(); it != pending_.end(); ++it) {
        if (it->path == path && it->series == series) {
            it->worker.detach(); // it has posted this and is ending
            pending_.erase(it);
            break;
        }
    }
    if (volume) {
        const QString told =
            volume->pet ? QString::fromStdString(petDisplayNotice(*volume->pet)) : QString();
        emit ready(path, series, adopt(std::move(volume), path, series));
        if (!told.isEmpty()) {
            emit notice(told);
        }
    } else if (stack) {
        auto* session = new SeriesSession(std::shared_ptr<const ImageStack>(std::move(stack)), path,
                                          series, this);
        sessions_.push_back(session);
        emit ready(path, series, session);
    } else {
        emit failed(path, series, error);
    }
}

SeriesSession* SeriesLibrary::sibling(SeriesSession* session) {
    if (!session->volume()) {
        return session; // a stack has no cursor or window to keep apart
    }
    auto* twin = new SeriesSession(session->volume(), session->path(), session->series(), this);
    sessions_.push_back(twin);
    return twin;
}

std::size_t SeriesLibrary::bytes() const {
    std::set<const void*> counted;
    std::size_t total = 0;
    for (const SeriesSession* s : sessions_) {
        if (counted
                .insert(s->volume() ? static_cast<const void*>(s->volume().get())
                                    : static_cast<const void*>(s->stack().get()))
                .second) {
            total += s->bytes();
        }
    }
    return total;
}

int SeriesLibrary::trim(const std::set<const SeriesSession*>& shown, std::size_t budgetBytes) {
    int dropped = 0;
    for (auto it = sessions_.begin(); it != sessions_.end() && bytes() > budgetBytes;) {
        if (shown.count(*it) != 0) {
            ++it;
            continue;
        }
        (*it)->deleteLater();
        it = sessions_.erase(it);
        ++dropped;
    }
    return dropped;
}

} // namespace lucent
