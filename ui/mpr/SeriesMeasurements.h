#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <QObject>

#include "core/measure/MeasurementDocument.h"
#include "core/volume/Volume.h"

namespace lucent {

// The measurements of one open series, shared by its MPR views (oblique planes
// included) and the measurement list: a MeasurementDocument (every edit one undo
// step) that says changed() after each edit, undo, redo and load. An ellipse's
// statistics are taken from the series' volume whenever it is added or changed.
// Persistence connects here: load() what was saved for seriesUid(), and save the
// document whenever changed() comes (revision() tells one state from another).
class SeriesMeasurements : public QObject {
    Q_OBJECT

public:
    SeriesMeasurements(std::shared_ptr<const Volume> volume, QObject* parent = nullptr);

    // The series (DICOM Series Instance UID; the file path for other formats).
    const std::string& seriesUid() const { return seriesUid_; }
    // The volume the statistics are taken from; the volume is the caller's to keep.
    void setVolume(std::shared_ptr<const Volume> volume);
    std::shared_ptr<const Volume> volume() const { return volume_.lock(); }

    const MeasurementDocument& document() const { return document_; }
    const std::vector<Measurement>& measurements() const { return document_.measurements(); }
    const Measurement* find(std::uint64_t id) const { return document_.find(id); }

    std::uint64_t add(Measurement m);
    bool change(Measurement m);
    bool rename(std::uint64_t id, const std::string& label);
    bool remove(std::uint64_t id);
    void clear();
    bool undo();
    bool redo();
    void load(std::vector<Measurement> measurements);

    // What other reports on the series hold that cannot be shown (one line an item).
    const std::vector<std::string>& notShown() const { return notShown_; }
    void setNotShown(std::vector<std::string> items);

    // The measurement the reader picked last (in a view or the list); 0: none.
    std::uint64_t selected() const { return selected_; }
    void select(std::uint64_t id);

signals:
    void changed();
    void selectionChanged(std::uint64_t id);

private:
    // An ellipse's statistics and unit from the volume, and on a PET series in SUVbw its
    // SUVmax, SUVmean and SUVpeak (measurementSuv); nothing for other kinds.
    void measure(Measurement& m) const;
    // After every edit: drops a selection that is gone and says changed().
    void edited();

    std::string seriesUid_;
    std::weak_ptr<const Volume> volume_;
    MeasurementDocument document_;
    std::uint64_t selected_ = 0;
    std::vector<std::string> notShown_;
};

} // namespace lucent
