#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <QObject>
#include <QPointer>
#include <QString>
#include <QTimer>

namespace lucent {

class MeasurementArchive;
class SeriesMeasurements;
class StudyStore;

// Keeps each series' measurements in the local study store as Lucent's DICOM SR
// (core/report/MeasurementArchive), as the reader works: what was saved (and what
// other reports on the series hold) is loaded when a series' measurements are made,
// and every change is saved kDelayMs after the last edit, and at once when this
// object goes (the window closes). A series that is not in the store keeps its
// measurements for the session only, and message() says so once.
class MeasurementAutosave : public QObject {
    Q_OBJECT

public:
    static constexpr int kDelayMs = 400;

    explicit MeasurementAutosave(QString storeFolder, QObject* parent = nullptr);
    ~MeasurementAutosave() override;

    void setStoreFolder(const QString& folder);
    void attach(SeriesMeasurements* measurements);
    // Saves every series changed since its last save now.
    void flush();

signals:
    void message(const QString& text, int timeoutMs);
    // A series' SR was written ("" when its last measurement went and the SR with it).
    void saved(const QString& seriesUid, const QString& reportInstanceUid);

private:
    struct Tracked {
        QPointer<SeriesMeasurements> measurements;
        std::uint64_t savedRevision = 0;
    };
    void save(Tracked& tracked);
    // The store and its archive, opened once: opening a store tidies its tmp/ folder,
    // and the archive reads each series' image headers once.
    MeasurementArchive& archive();

    QString folder_;
    std::unique_ptr<StudyStore> store_;
    std::unique_ptr<MeasurementArchive> archive_;
    std::vector<Tracked> tracked_;
    QTimer timer_;
};

} // namespace lucent
