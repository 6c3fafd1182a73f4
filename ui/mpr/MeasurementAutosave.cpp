#include "ui/mpr/MeasurementAutosave.h"

#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>

#include "core/report/MeasurementArchive.h"
#include "core/report/ReferencedSeries.h"
#include "core/store/StudyStore.h"
#include "ui/mpr/SeriesMeasurements.h"

namespace lucent {

MeasurementAutosave::MeasurementAutosave(QString storeFolder, QObject* parent)
    : QObject(parent), folder_(std::move(storeFolder)) {
    timer_.setSingleShot(true);
    timer_.setInterval(kDelayMs);
    connect(&timer_, &QTimer::timeout, this, &MeasurementAutosave::flush);
}

MeasurementAutosave::~MeasurementAutosave() {
    flush();
}

void MeasurementAutosave::setStoreFolder(const QString& folder) {
    archive_.reset();
    store_.reset();
    folder_ = folder;
}

MeasurementArchive& MeasurementAutosave::archive() {
    if (!archive_) {
        store_ = std::make_unique<StudyStore>(folder_.toStdString());
        const QString software =
            (QStringLiteral("Lucent ") + QCoreApplication::applicationVersion()).trimmed();
        archive_ = std::make_unique<MeasurementArchive>(*store_, software.toStdString());
    }
    return *archive_;
}

void MeasurementAutosave::attach(SeriesMeasurements* measurements) {
    const QString uid = QString::fromStdString(measurements->seriesUid());
    bool stored = false;
    // No index, no store: one is not made just because a series was opened.
    const bool storeExists =
        !folder_.isEmpty() &&
        QFileInfo::exists(QDir(folder_).filePath(QStringLiteral("index.sqlite")));
    if (storeExists && !uid.isEmpty()) {
        try {
            MeasurementArchive& reports = archive();
            stored = !store_->instancesOf(uid.toStdString()).empty();
            if (stored) {
                MeasurementArchive::Loaded loaded = reports.load(uid.toStdString());
                measurements->load(std::move(loaded.measurements));
                measurements->setNotShown(std::move(loaded.notShown));
            }
        } catch (const std::exception& e) {
            emit message(tr("Saved measurements could not be read: %1").arg(e.what()), 0);
        }
    }
    if (!stored) {
        emit message(tr("Measurements of this series are kept for this session only: it is not "
                        "in the study store"),
                     8000);
        return;
    }
    tracked_.push_back({measurements, measurements->document().revision()});
    connect(measurements, &SeriesMeasurements::changed, this, [this] { timer_.start(); });
}

void MeasurementAutosave::flush() {
    timer_.stop();
    for (Tracked& t : tracked_) {
        if (t.measurements != nullptr && t.measurements->document().revision() != t.savedRevision) {
            save(t);
        }
    }
    std::erase_if(tracked_, [](const Tracked& t) { return t.measurements == nullptr; });
}

void MeasurementAutosave::save(Tracked& tracked) {
    const SeriesMeasurements& m = *tracked.measurements;
    try {
        const std::string sr = archive().save(m.seriesUid(), m.measurements());
        tracked.savedRevision = m.document().revision();
        emit saved(QString::fromStdString(m.seriesUid()), QString::fromStdString(sr));
    } catch (const std::exception& e) {
        // Kept unsaved: the next edit tries again; what was stored before stays.
        emit message(tr("Measurements not saved: %1").arg(e.what()), 0);
    }
}

} // namespace lucent
