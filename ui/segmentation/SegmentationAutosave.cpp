#include "ui/segmentation/SegmentationAutosave.h"

#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>

#include "core/store/StudyStore.h"

namespace lucent {

SegmentationAutosave::SegmentationAutosave(QString storeFolder, QObject* parent)
    : QObject(parent), folder_(std::move(storeFolder)) {
    timer_.setSingleShot(true);
    timer_.setInterval(kDelayMs);
    connect(&timer_, &QTimer::timeout, this, &SegmentationAutosave::flush);
    poll_.setInterval(kPollMs);
    connect(&poll_, &QTimer::timeout, this, &SegmentationAutosave::poll);
}

SegmentationAutosave::~SegmentationAutosave() {
    flush();
}

void SegmentationAutosave::setStoreFolder(const QString& folder) {
    flush();
    tracked_.clear();
    poll_.stop();
    archive_.reset();
    store_.reset();
    folder_ = folder;
}

bool SegmentationAutosave::storeExists() const {
    // No index, no store: one is not made just because a series was segmented.
    return !folder_.isEmpty() &&
           QFileInfo::exists(QDir(folder_).filePath(QStringLiteral("index.sqlite")));
}

SegmentationArchive& SegmentationAutosave::archive() {
    if (!archive_) {
        store_ = std::make_unique<StudyStore>(folder_.toStdString());
        const QString software =
            (QStringLiteral("Lucent ") + QCoreApplication::applicationVersion()).trimmed();
        archive_ = std::make_unique<SegmentationArchive>(*store_, software.toStdString());
    }
    return *archive_;
}

SegmentationArchive::LoadResult SegmentationAutosave::load(const QString& seriesUid,
                                                           const VolumeGeometry& grid) {
    SegmentationArchive::LoadResult result;
    if (!storeExists() || seriesUid.isEmpty()) {
        return result;
    }
    try {
        result = archive().load(seriesUid.toStdString(), grid);
    } catch (const std::exception& e) {
        result.errors.push_back(e.what());
    }
    for (const std::string& e : result.errors) {
        emit message(tr("A stored segmentation could not be read: %1").arg(e.c_str()), 0);
    }
    return result;
}

bool SegmentationAutosave::attach(Segmentation* segmentation, const QString& seriesUid) {
    bool stored = false;
    if (storeExists() && !seriesUid.isEmpty()) {
        try {
            archive();
            stored = !store_->instancesOf(seriesUid.toStdString()).empty();
        } catch (const std::exception& e) {
            emit message(tr("The study store could not be opened: %1").arg(e.what()), 0);
        }
    }
    if (!stored) {
        emit message(tr("Segments of this series are kept for this session only: it is not in "
                        "the study store"),
                     8000);
        return false;
    }
    detach(segmentation);
    const std::uint64_t now = segmentation->revision();
    tracked_.push_back({segmentation, seriesUid, now, now});
    poll_.start();
    return true;
}

void SegmentationAutosave::detach(const Segmentation* segmentation) {
    for (Tracked& t : tracked_) {
        if (t.segmentation == segmentation && t.segmentation->revision() != t.savedRevision) {
            save(t);
        }
    }
    std::erase_if(tracked_, [&](const Tracked& t) { return t.segmentation == segmentation; });
    if (tracked_.empty()) {
        poll_.stop();
    }
}

void SegmentationAutosave::changed() {
    timer_.start();
}

void SegmentationAutosave::poll() {
    for (Tracked& t : tracked_) {
        if (t.segmentation->revision() != t.seenRevision) {
            t.seenRevision = t.segmentation->revision();
            timer_.start(); // debounced: saved kDelayMs after the last change seen
        }
    }
}

void SegmentationAutosave::flush() {
    timer_.stop();
    for (Tracked& t : tracked_) {
        if (t.segmentation->revision() != t.savedRevision) {
            save(t);
        }
    }
}

void SegmentationAutosave::save(Tracked& tracked) {
    try {
        const std::uint64_t revision = tracked.segmentation->revision();
        const std::string sop =
            archive().save(tracked.seriesUid.toStdString(), *tracked.segmentation);
        tracked.savedRevision = revision;
        tracked.seenRevision = revision;
        emit saved(tracked.seriesUid, QString::fromStdString(sop));
    } catch (const std::exception& e) {
        // Kept unsaved: the next edit tries again; what was stored before stays.
        emit message(tr("Segments not saved: %1").arg(e.what()), 0);
    }
}

} // namespace lucent
